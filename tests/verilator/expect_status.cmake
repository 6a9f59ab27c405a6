# expect_status.cmake: runs CMD (a ;-list) and passes only if it exits with EXPECT_STATUS
# and its output matches every regular expression in EXPECT_REGEX (a ;-list).
# Used for the tests whose point is that harris-cosim verilate *fails* in a named way.
execute_process(COMMAND ${CMD} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(all "${out}${err}")
message("${all}")
if(NOT status STREQUAL "${EXPECT_STATUS}")
  message(FATAL_ERROR "exit status ${status}, expected ${EXPECT_STATUS}")
endif()
foreach(re IN LISTS EXPECT_REGEX)
  if(NOT all MATCHES "${re}")
    message(FATAL_ERROR "output does not match '${re}'")
  endif()
endforeach()
