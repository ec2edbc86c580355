# ctest c_api_example: import the Replica room with the smql shell, then query
# it with the C example, once successfully and once with a syntax error.
# Inputs (-D): SMQL (shell), EXAMPLE (smql_c_example), DATA (replica file), WORK (scratch dir).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(DB ${WORK}/db)

execute_process(COMMAND ${SMQL} import replica ${DATA} --db ${DB}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "smql import failed (${rc}):\n${out}${err}")
endif()

execute_process(COMMAND ${EXAMPLE} ${DB} "FIND cushion WHERE on(sofa) PATH"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "example output:\n${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "smql_c_example failed (${rc}):\n${err}")
endif()
foreach(expected "id\tcategory" "cushion" "center (" "\"category\":\"cushion\"")
  string(FIND "${out}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the example output lacks '${expected}'")
  endif()
endforeach()

execute_process(COMMAND ${EXAMPLE} ${DB} "FIND cushion WHERE on("
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "syntax error at line 1")
  message(FATAL_ERROR "a syntax error should exit non-zero with the message, got ${rc}:\n${err}")
endif()
file(REMOVE_RECURSE ${WORK})
