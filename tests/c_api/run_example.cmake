# ctest c_api_example: import the Replica room with the smql shell, then query
# it with the C example, once successfully and once with a syntax error.
# Then the prepared-statement example binds values, steps the rows and runs it again.
# Inputs (-D): SMQL (shell), EXAMPLE (smql_c_example), PREPARED (smql_c_prepared_example),
# DATA (replica file), WORK (scratch dir).

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

execute_process(COMMAND ${PREPARED} ${DB} "FIND ? WHERE on(?) LIMIT ?" cushion sofa 2
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "prepared example output:\n${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "smql_c_prepared_example failed (${rc}):\n${err}")
endif()
foreach(expected "\"category\":\"cushion\"" "run 1: 2 row(s)" "run 2: 2 row(s)")
  string(FIND "${out}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the prepared example output lacks '${expected}'")
  endif()
endforeach()

# A value with a quote is a name like any other: an unknown category, not a syntax error.
execute_process(COMMAND ${PREPARED} ${DB} "FIND ?" "o'brien's mug"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "unknown category 'o'brien's mug'")
  message(FATAL_ERROR "an unknown bound name should exit non-zero naming it, got ${rc}:\n${err}")
endif()
file(REMOVE_RECURSE ${WORK})
