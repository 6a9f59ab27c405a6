# hc_vhdl_generics(PKG): reads the DEF_<GENERIC> constants of rtl/harris_pkg.vhd, in file
# order, and sets in the caller's scope the text testbenches need to pass every generic of
# harris_top through (configure_file placeholders):
#   HC_TB_GENERIC_DECLS  "    IMG_WIDTH : positive := DEF_IMG_WIDTH;" ... one per line, the
#                        last without its ';' (the template adds it when more generics follow)
#   HC_TB_GENERIC_MAP    "IMG_WIDTH => IMG_WIDTH, ..."
#   HC_TB_GENERIC_LIST   "IMG_WIDTH, IMG_HEIGHT, ..."
# The package is a configure dependency: a new DEF_* constant re-runs CMake, so the
# testbenches follow the formats table (tests/model/vhdl_agreement_test.cpp checks that the
# constants and the table agree, in order).
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
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${pkg})
endfunction()
