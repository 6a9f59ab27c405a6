# wide_response.cmake: the Verilator flow at a configuration of the sweep spec whose response is
# wider than 32 bits, where find_max's most negative value is a constant GHDL writes as a bit
# string (cosim/ghdl_verilog.hpp). The configuration's fields are taken from the spec; the
# gate (GHDL, Verilator, model on frames past find_max's period) and a lock-step run with every
# register compared must pass with 0 mismatches.
#   cmake -DCLI=harris-cosim -DSPEC=sweep/configs/bit-widths.json -DNAME=tight-m3-b2 -DWORK=dir -P wide_response.cmake
include(${CMAKE_CURRENT_LIST_DIR}/../run_expecting.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(READ ${SPEC} spec)
string(JSON n LENGTH "${spec}" configs)
math(EXPR last "${n} - 1")
set(config "")
foreach(i RANGE ${last})
  string(JSON name GET "${spec}" configs ${i} name)
  if(name STREQUAL NAME)
    string(JSON config GET "${spec}" configs ${i})
  endif()
endforeach()
if(config STREQUAL "")
  message(FATAL_ERROR "${SPEC} has no configuration ${NAME}")
endif()
string(JSON config REMOVE "${config}" name)
string(JSON resp_w GET "${config}" resp_w)
if(resp_w LESS_EQUAL 32)
  message(FATAL_ERROR "${NAME}'s resp_w is ${resp_w}: no constant wider than 32 bits to test")
endif()
file(WRITE ${WORK}/${NAME}.json "${config}\n")
# 16x12: find_max's period is (12/2 - 3) * (16/2 + 3) * 4 = 132 writes, 3 frames run past it
hc_run_expecting(0 "verilate at ${NAME} (resp_w ${resp_w})" " (4: GHDL and Verilator disagree; 1: a mismatch)"
                 ${CLI} verilate --config ${WORK}/${NAME}.json --obs --pattern random --size 16x12 --frames 3 --seed 7
                 --json ${WORK}/run.json)
file(READ ${WORK}/run.json run)
string(JSON mismatches GET "${run}" mismatches writes)
if(NOT mismatches EQUAL 0)
  message(FATAL_ERROR "${mismatches} mismatching writes")
endif()
message(STATUS "PASS: ${NAME} (resp_w ${resp_w}): gate passed, 0 mismatches")
