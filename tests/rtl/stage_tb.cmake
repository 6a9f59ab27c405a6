# stage_tb.cmake: one entity bench, <stem>_tb.vhd, from the skeleton every bench shares
# (stage_tb.vhd.in: the generics RANDOM_VECTORS and SEED, the process that hands the generics
# to C++, opens the bench, resets the DUT, loops over the vectors C++ chooses and checks each,
# and finishes with the bridge's status) and the bench's parts (<stem>_tb.vhd-part), sections
# that start with a line `--% <name>`:
#   purpose       the header comment: what the bench proves and how C++ drives it
#   generics      the DUT's generics as the bench's, one a line, each ending in ';'; each is
#                 also handed to C++ (stage_generic(STAGE_G_<NAME>, <NAME>))
#   declarations  OUT_W (the width of the packed outputs) and the signals
#   dut           the DUT's instance
#   step          one loop turn: apply stage_input(k), advance (stage_clock, or a wait for a
#                 combinational entity), pack the outputs into buf
#   reset         optional; present (and empty) for an entity without a reset: no stage_reset
#   cmake -DSTEM=<stem> -DPART=<part file> -DTEMPLATE=stage_tb.vhd.in -DOUT=<file> -P stage_tb.cmake
file(READ ${PART} text)
set(STEM ${STEM})
string(TOUPPER ${STEM} STEM_UPPER)
foreach(section purpose generics declarations dut step reset)
  string(FIND "${text}" "--% ${section}\n" at)
  string(FIND "${text}" "--% ${section}" at_last)   # a last section may end the file
  if(at EQUAL -1 AND NOT at_last EQUAL -1)
    set(at ${at_last})
  endif()
  if(at EQUAL -1)
    if(NOT section STREQUAL "reset")
      message(FATAL_ERROR "${PART}: no section '--% ${section}'")
    endif()
    set(body_${section} "")
    set(has_${section} FALSE)
    continue()
  endif()
  set(has_${section} TRUE)
  string(LENGTH "--% ${section}\n" n)
  math(EXPR from "${at} + ${n}")
  string(SUBSTRING "${text}" ${from} -1 rest)
  string(FIND "${rest}" "\n--% " end)
  if(end EQUAL -1)
    string(LENGTH "${rest}" end)
  endif()
  string(SUBSTRING "${rest}" 0 ${end} body)
  string(REGEX REPLACE "\n+$" "" body "${body}")
  set(body_${section} "${body}")
endforeach()
set(PURPOSE "${body_purpose}")
set(GENERICS "${body_generics}")
set(DECLARATIONS "${body_declarations}")
set(DUT "${body_dut}")
set(STEP "${body_step}")
string(REGEX MATCHALL "(^|\n) *[A-Z][A-Z0-9_]* *:" names "${body_generics}")
set(GENERIC_CALLS "")
foreach(n IN LISTS names)
  string(REGEX REPLACE "^\n? *([A-Z][A-Z0-9_]*) *:$" "\\1" n "${n}")
  if(GENERIC_CALLS)
    string(APPEND GENERIC_CALLS "\n")
  endif()
  string(APPEND GENERIC_CALLS "    rc := stage_generic(STAGE_G_${n}, ${n});")
endforeach()
if(has_reset)
  set(RESET "    -- no reset: a combinational entity")
else()
  set(RESET "    stage_reset(clk, rst);")
endif()
configure_file(${TEMPLATE} ${OUT} @ONLY)
file(TOUCH ${OUT})
