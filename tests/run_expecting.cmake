# run_expecting.cmake: for cmake -P test scripts. hc_run_expecting(STATUS WHAT HINT COMMAND...)
# runs COMMAND, prints "WHAT: status N" and its output, and stops the script with
# "WHAT: status N, expected STATUS HINT" unless COMMAND exited with STATUS. Its standard
# output and error are left in `out` and `err` of the caller.
function(hc_run_expecting status what hint)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  message(STATUS "${what}: status ${rc}\n${o}${e}")
  if(NOT rc EQUAL ${status})
    message(FATAL_ERROR "${what}: status ${rc}, expected ${status}${hint}")
  endif()
  set(out "${o}" PARENT_SCOPE)
  set(err "${e}" PARENT_SCOPE)
endfunction()
