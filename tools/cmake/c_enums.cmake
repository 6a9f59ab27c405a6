# hc_c_enums(HEADER PREFIX): for every enumerator `PREFIXNAME = <integer>` of a C header,
# sets the CMake variable PREFIXNAME to its value in the caller's scope, so that a VHDL
# package made by configure_file() takes its numbers from the header that owns them.
# The header is a configure dependency: editing it re-runs CMake.
function(hc_c_enums header prefix)
  file(READ ${header} text)
  string(REGEX MATCHALL "${prefix}[A-Z0-9_]+[ \t]*=[ \t]*[0-9]+" items "${text}")
  if(NOT items)
    message(FATAL_ERROR "hc_c_enums: no ${prefix}* enumerators in ${header}")
  endif()
  foreach(item IN LISTS items)
    string(REGEX REPLACE "^(${prefix}[A-Z0-9_]+)[ \t]*=[ \t]*([0-9]+)$" "\\1;\\2" kv "${item}")
    list(GET kv 0 name)
    list(GET kv 1 value)
    set(${name} ${value} PARENT_SCOPE)
  endforeach()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${header})
endfunction()
