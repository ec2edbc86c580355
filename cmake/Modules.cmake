# smql's modules (model/module.hpp): shared libraries of its own that a library loads (dlopen) on
# first use, so that the programs that never need them never load what they bring.
#
#   smql_module(<target> <output name> <loaded by> SOURCES <file>... LINK <library>...)
#
# builds lib<output name>.so, installs it in the library folder and tells <loaded by> where the build
# tree holds it (<OUTPUT NAME>_MODULE_BUILT, e.g. SMQL_HTTP_MODULE_BUILT for smql_http).
function(smql_module target output loader)
  cmake_parse_arguments(PARSE_ARGV 3 ARG "" "" "SOURCES;LINK")
  add_library(${target} MODULE ${ARG_SOURCES})
  set_target_properties(${target} PROPERTIES OUTPUT_NAME ${output} CXX_VISIBILITY_PRESET hidden
                        VISIBILITY_INLINES_HIDDEN ON)
  target_link_libraries(${target} PRIVATE ${ARG_LINK})
  # A missing symbol is a link error here, not at the first use; the sanitizers' runtime, which the
  # fuzzing build leaves to the executable, is the one exception.
  if(NOT SMQL_FUZZ)
    target_link_options(${target} PRIVATE -Wl,--no-undefined)
  endif()
  string(TOUPPER ${output} name)
  target_compile_definitions(${loader} PRIVATE ${name}_MODULE_BUILT="$<TARGET_FILE:${target}>")
  add_dependencies(${loader} ${target})
  install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
endfunction()
