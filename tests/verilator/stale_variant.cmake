# stale_variant.cmake: an RTL file edited after the gate passed is gated again, never passed
# from the recorded verdict. A scratch copy of rtl/m_products.vhd replaces the design's
# (--variant): unedited, the gate passes; then the copy's `b` slice is shifted by one bit in
# place (same path, new contents) and the gate must report an RTL fault (status 1), not
# "recorded earlier".
#   cmake -DCLI=harris-cosim -DRTL=<src>/rtl -DWORK=dir -P stale_variant.cmake
include(${CMAKE_CURRENT_LIST_DIR}/../run_expecting.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
configure_file(${RTL}/m_products.vhd ${WORK}/m_products.vhd COPYONLY)
hc_run_expecting(0 "the gate on an unedited copy of the RTL" ""
                 ${CLI} verilate --gate-only --variant ${WORK}/m_products.vhd --json ${WORK}/before.json)
file(READ ${WORK}/m_products.vhd text)
string(REPLACE "b <= b_full(M_PROD_W - 1 downto M_DROP);" "b <= b_full(M_PROD_W - 2 downto M_DROP - 1);" edited "${text}")
if(edited STREQUAL text)
  message(FATAL_ERROR "the edit did not apply: m_products.vhd has no `b <= b_full(M_PROD_W - 1 downto M_DROP);`")
endif()
file(WRITE ${WORK}/m_products.vhd "${edited}")
hc_run_expecting(1 "the gate on the edited copy" " (an RTL fault; 0 would be a stale pass)"
                 ${CLI} verilate --gate-only --variant ${WORK}/m_products.vhd --json ${WORK}/after.json)
if(err MATCHES "recorded earlier")
  message(FATAL_ERROR "the edited RTL's gate verdict came from the record of the unedited one")
endif()
if(NOT err MATCHES "RTL fault")
  message(FATAL_ERROR "the gate does not name the RTL fault")
endif()
message(STATUS "PASS: the edit was gated again and reported as an RTL fault")
