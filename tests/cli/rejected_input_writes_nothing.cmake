# rejected_input_writes_nothing.cmake: a command that rejects its input (status 2) writes
# nothing: no file appears in its working directory or in --out, and an output already in
# --out keeps its bytes.
#   cmake -DWORK=dir -DCMD="harris-cosim;eval;...;--out;@OUT@" -P rejected_input_writes_nothing.cmake
# @OUT@ in CMD is replaced by WORK/out.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/out)
file(WRITE ${WORK}/out/summary.md "an earlier run's report\n")
file(WRITE ${WORK}/out/totals.json "{\"earlier\": true}\n")
file(GLOB_RECURSE before RELATIVE ${WORK} LIST_DIRECTORIES true ${WORK}/*)
string(REPLACE "@OUT@" "${WORK}/out" cmd "${CMD}")
execute_process(COMMAND ${cmd} WORKING_DIRECTORY ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}${err}")
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "expected status 2 (bad input), got ${rc}")
endif()
file(GLOB_RECURSE after RELATIVE ${WORK} LIST_DIRECTORIES true ${WORK}/*)
if(NOT before STREQUAL after)
  message(FATAL_ERROR "the rejected run changed the files: before [${before}], after [${after}]")
endif()
file(READ ${WORK}/out/summary.md s)
file(READ ${WORK}/out/totals.json t)
if(NOT s STREQUAL "an earlier run's report\n" OR NOT t STREQUAL "{\"earlier\": true}\n")
  message(FATAL_ERROR "the rejected run changed an existing output")
endif()
message(STATUS "PASS: status 2, nothing written, the earlier outputs untouched")
