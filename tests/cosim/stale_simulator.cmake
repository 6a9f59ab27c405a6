# stale_simulator.cmake: a GHDL simulator older than an RTL file it was built from is
# refused (status 3) with the changed file and the command to run named, never run; so is one
# whose RTL differs from the copy the build took before analysing it, whatever the dates.
# Editing an RTL file after the build is what makes a simulator stale; the test makes the
# same states without touching rtl/: the back end's simulator (the gcc/llvm executable, the
# mcode analysis stamp) is dated back to 2000, then its date is restored; then the build's
# copy of m_products.vhd is edited, then restored.
#   cmake -DCLI=harris-cosim -DSIM_DIR=<build>/cosim -DBACKEND=gcc|llvm|mcode -DWORK=dir -P stale_simulator.cmake
# Runs the simulator; FATAL_ERROR unless it is refused with status 3 and a message matching
# `pattern` (`what` names the state in the failure).
function(expect_refusal what pattern)
  execute_process(COMMAND ${CLI} rtl --backend ${BACKEND} --pattern flat --size 20x10 --frames 1 --quiet
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${out}${err}")
  if(NOT rc EQUAL 3)
    set(failed "${what} ${BACKEND} simulator ran: status ${rc}, expected 3" PARENT_SCOPE)
  elseif(NOT err MATCHES "${pattern}")
    set(failed "the refusal of ${what} ${BACKEND} simulator does not name the file and the command to run" PARENT_SCOPE)
  endif()
endfunction()

if(BACKEND STREQUAL "mcode")
  set(stamp ${SIM_DIR}/ghdl-mcode/analysed.stamp)
else()
  set(stamp ${SIM_DIR}/harris_top_tb_${BACKEND})
endif()
set(keep ${WORK}/stamp-time)
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND touch -r ${stamp} ${keep})
execute_process(COMMAND touch -d 2000-01-01 ${stamp})
expect_refusal("a stale" "simulator is older than [^ ]*/rtl/[a-z_]+\\.vhd, which changed since it was built: run `cmake --build ")
execute_process(COMMAND touch -r ${keep} ${stamp})
if(failed)
  message(FATAL_ERROR "${failed}")
endif()

set(copy ${SIM_DIR}/ghdl-${BACKEND}/inputs/m_products.vhd)
if(NOT EXISTS ${copy})
  message(FATAL_ERROR "the build kept no copy of the RTL it analysed: ${copy}")
endif()
file(READ ${copy} original)
file(APPEND ${copy} "-- an edit the simulator was not built from\n")
expect_refusal("a" "simulator was built from another [^ ]*/rtl/m_products\\.vhd \\(its copy [^ ]* differs\\): run `cmake --build ")
file(WRITE ${copy} "${original}")
if(failed)
  message(FATAL_ERROR "${failed}")
endif()
