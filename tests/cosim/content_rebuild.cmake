# content_rebuild.cmake: an RTL edit that leaves the file older than the simulator (as
# `cp -p`, `rsync -t` or `tar x` of an older copy do) is rebuilt by `cmake --build`, and the
# rebuilt simulator catches the mutant. In a scratch copy of the source tree (rtl/ of the
# tree under test is never touched), configured without tests and without optimisation (the
# VHDL's rebuild is the subject, and an unoptimised C++ side builds faster), only the mcode
# simulator is built (its C++ side: hc_util, hc_model, hc_cosim, the bridge):
#   1. build, run the co-simulation: pass;
#   2. mutate rtl/m_products.vhd (b = ix*ix instead of ix*iy), date it 2000-01-01, build again;
#   3. the simulator was re-analysed (its stamp is newer), and the run fails with a mismatch
#      (status 1) at the M stage.
#   cmake -DCLI=harris-cosim -DSRC=<source tree> -DWORK=<scratch> -P content_rebuild.cmake
function(run_checked)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "`${ARGN}` failed (status ${rc}):\n${out}${err}")
  endif()
endfunction()

function(cosim expect_rc expect_pattern)
  execute_process(COMMAND ${CLI} rtl --backend mcode --sim-dir ${WORK}/build/cosim
                          --pattern blocks --size 40x30 --frames 2 --quiet
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "co-simulation: status ${rc}\n${out}${err}")
  if(NOT rc EQUAL expect_rc)
    message(FATAL_ERROR "the co-simulation of the scratch build returned ${rc}, expected ${expect_rc}")
  endif()
  if(NOT "${out}${err}" MATCHES "${expect_pattern}")
    message(FATAL_ERROR "the co-simulation's report does not match '${expect_pattern}'")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/src)
# the source tree without build trees, outputs and git data
file(GLOB entries RELATIVE ${SRC} ${SRC}/*)
foreach(e IN LISTS entries)
  if(e MATCHES "^(build.*|out|\\.git)$")
    continue()
  endif()
  file(COPY ${SRC}/${e} DESTINATION ${WORK}/src)
endforeach()

run_checked(${CMAKE_COMMAND} -S ${WORK}/src -B ${WORK}/build -DCMAKE_BUILD_TYPE=Debug -DBUILD_TESTING=OFF)
run_checked(${CMAKE_COMMAND} --build ${WORK}/build --target ghdl_sim_mcode -j2)
set(stamp ${WORK}/build/cosim/ghdl-mcode/analysed.stamp)
file(TIMESTAMP ${stamp} first "%s")
cosim(0 "")

set(rtl ${WORK}/src/rtl/m_products.vhd)
file(READ ${rtl} text)
string(REPLACE "b_full <= resize(ix * iy, M_PROD_W);" "b_full <= resize(ix * ix, M_PROD_W);" mutated "${text}")
if(mutated STREQUAL text)
  message(FATAL_ERROR "the mutation found nothing to change in ${rtl}")
endif()
file(WRITE ${rtl} "${mutated}")
run_checked(touch -d 2000-01-01 ${rtl})
# one second on, so that a rebuild dates the stamp differently from the first build
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1)
run_checked(${CMAKE_COMMAND} --build ${WORK}/build --target ghdl_sim_mcode -j2)
file(TIMESTAMP ${stamp} second "%s")
if(NOT second GREATER first)
  message(FATAL_ERROR "the build did not re-analyse the RTL after an old-dated edit of ${rtl}")
endif()
cosim(1 "m_products|stage M|m_a|m_b")
file(REMOVE_RECURSE ${WORK})
