# ctest c_api_install: `cmake --install` into a scratch prefix, then build a
# small C program against the installed header and library twice, once with
# pkg-config and once with find_package(smql), and run both.
# Inputs (-D): BUILD_DIR, WORK (scratch dir), CONSUMER (C source), CC, PKG_CONFIG, LIBDIR (relative).
file(REMOVE_RECURSE ${WORK})
set(PREFIX ${WORK}/prefix)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
foreach(file include/smql.h ${LIBDIR}/libsmql.so ${LIBDIR}/libsmql.so.0 ${LIBDIR}/pkgconfig/smql.pc
             ${LIBDIR}/cmake/smql/smqlConfig.cmake ${LIBDIR}/cmake/smql/smqlConfigVersion.cmake)
  if(NOT EXISTS ${PREFIX}/${file})
    message(FATAL_ERROR "not installed: ${file}")
  endif()
endforeach()

# pkg-config, the way a Makefile would use it.
set(ENV{PKG_CONFIG_PATH} ${PREFIX}/${LIBDIR}/pkgconfig)
run(${PKG_CONFIG} --cflags --libs smql)
separate_arguments(flags UNIX_COMMAND "${out}")
run(${CC} -std=c99 -Wall -Wextra -pedantic -Werror ${CONSUMER} ${flags} -o ${WORK}/consumer-pkg-config)
set(ENV{LD_LIBRARY_PATH} ${PREFIX}/${LIBDIR})
run(${WORK}/consumer-pkg-config)
message(STATUS "pkg-config consumer: ${out}")

# find_package, the way a CMake project would (its RPATH finds the library).
set(ENV{LD_LIBRARY_PATH} "")
file(WRITE ${WORK}/cmake-consumer/CMakeLists.txt "cmake_minimum_required(VERSION 3.25)
project(smql_consumer LANGUAGES C)
find_package(smql 0.1 REQUIRED)
add_executable(consumer ${CONSUMER})
target_link_libraries(consumer PRIVATE smql::smql)
")
run(${CMAKE_COMMAND} -S ${WORK}/cmake-consumer -B ${WORK}/cmake-consumer/build -DCMAKE_PREFIX_PATH=${PREFIX}
    -DCMAKE_C_COMPILER=${CC})
run(${CMAKE_COMMAND} --build ${WORK}/cmake-consumer/build)
run(${WORK}/cmake-consumer/build/consumer)
message(STATUS "find_package consumer: ${out}")
file(REMOVE_RECURSE ${WORK})
