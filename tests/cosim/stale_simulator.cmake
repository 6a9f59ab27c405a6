# stale_simulator.cmake: a GHDL simulator older than an RTL file it was built from is
# refused (status 3) with the changed file and the command to run named, never run.
# The mcode back end's analysis stamp is dated back to 2000 for the test, then restored.
set(stamp ${SIM_DIR}/ghdl-mcode/analysed.stamp)
set(keep ${WORK}/stamp-time)
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND touch -r ${stamp} ${keep})
execute_process(COMMAND touch -d 2000-01-01 ${stamp})
execute_process(COMMAND ${CLI} rtl --backend mcode --pattern flat --size 20x10 --frames 1 --quiet
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
execute_process(COMMAND touch -r ${keep} ${stamp})
message(STATUS "${out}${err}")
if(NOT rc EQUAL 3)
  message(FATAL_ERROR "a stale simulator ran: status ${rc}, expected 3")
endif()
if(NOT err MATCHES "simulator is older than [^ ]*/rtl/[a-z_]+\\.vhd, which changed since it was built: run `cmake --build ")
  message(FATAL_ERROR "the refusal does not name the changed file and the command to run")
endif()
