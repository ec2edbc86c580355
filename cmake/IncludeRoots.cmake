# Include roots per library: each library sees its own headers and those of the libraries it links,
# nothing else, so an upward include (storage including the engine, the model including storage)
# fails to compile instead of quietly becoming a dependency. A library's root is a folder in the
# build tree with links to the source folders (or headers) it owns, under their usual paths, so
# every `#include "storage/codec.hpp"` reads the same as before.
#
#   smql_include_root(<target> PUBLIC|PRIVATE <path relative to the source root>...)
function(smql_include_root target visibility)
  set(root ${CMAKE_BINARY_DIR}/include-roots/${target})
  foreach(path IN LISTS ARGN)
    if(NOT EXISTS ${PROJECT_SOURCE_DIR}/${path})
      message(FATAL_ERROR "smql_include_root(${target}): ${path} does not exist")
    endif()
    get_filename_component(parent ${root}/${path} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${path} ${root}/${path} SYMBOLIC)
  endforeach()
  target_include_directories(${target} ${visibility} ${root})
endfunction()
