# hc_vhdl_generics(PKG): reads the DEF_<GENERIC> constants of rtl/harris_pkg.vhd, in file
# order, and sets in the caller's scope the text testbenches need to pass every generic of
# harris_top through (configure_file placeholders):
#   HC_TB_GENERIC_DECLS  "    IMG_WIDTH : positive := DEF_IMG_WIDTH;" ... one per line, the
#                        last without its ';' (the template adds it when more generics follow)
#   HC_TB_GENERIC_MAP    "IMG_WIDTH => IMG_WIDTH, ..."
#   HC_TB_GENERIC_LIST   "IMG_WIDTH, IMG_HEIGHT, ..."
# tests/model/vhdl_agreement_test.cpp checks that the constants and the formats table agree,
# in order.
#
# hc_vhdl_testbench(<template> <output> <content stamp>): <output> made from <template> at
# build time (a custom command), so that an edit of the package, whatever its date, remakes
# the testbench: the command depends on the stamp of hc_content_stamp() that lists the
# package and the template. Script mode, the work of that command:
#   cmake -DPKG=harris_pkg.vhd -DIN=<template> -DOUT=<output> -P vhdl_generics.cmake
function(hc_vhdl_generics pkg)
  file(STRINGS ${pkg} lines REGEX "^[ \t]*constant[ \t]+DEF_[A-Z0-9_]+[ \t]*:[ \t]*(positive|natural)")
  set(decls "")
  set(map "")
  set(list "")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^[ \t]*constant[ \t]+DEF_([A-Z0-9_]+)[ \t]*:[ \t]*(positive|natural).*$" "\\1;\\2" nt "${line}")
    list(GET nt 0 name)
    list(GET nt 1 type)
    if(decls)
      string(APPEND decls ";\n")
      string(APPEND map ", ")
      string(APPEND list ", ")
    endif()
    string(APPEND decls "    ${name} : ${type} := DEF_${name}")
    string(APPEND map "${name} => ${name}")
    string(APPEND list "${name}")
  endforeach()
  if(NOT list)
    message(FATAL_ERROR "hc_vhdl_generics: no DEF_* constants in ${pkg}")
  endif()
  set(HC_TB_GENERIC_DECLS "${decls}" PARENT_SCOPE)
  set(HC_TB_GENERIC_MAP "${map}" PARENT_SCOPE)
  set(HC_TB_GENERIC_LIST "${list}" PARENT_SCOPE)
endfunction()

if(CMAKE_SCRIPT_MODE_FILE)
  hc_vhdl_generics(${PKG})
  configure_file(${IN} ${OUT} @ONLY)
  file(TOUCH ${OUT})   # dated by this run even when its text is unchanged
  return()
endif()

set(HC_VHDL_GENERICS_SCRIPT ${CMAKE_CURRENT_LIST_FILE})

function(hc_vhdl_testbench template output stamp)
  add_custom_command(OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DPKG=${PROJECT_SOURCE_DIR}/rtl/harris_pkg.vhd -DIN=${template}
            -DOUT=${output} -P ${HC_VHDL_GENERICS_SCRIPT}
    DEPENDS ${PROJECT_SOURCE_DIR}/rtl/harris_pkg.vhd ${template} ${stamp} ${HC_VHDL_GENERICS_SCRIPT}
    COMMENT "Generating ${output} from the DEF_* constants of harris_pkg.vhd"
    VERBATIM)
endfunction()
