# Rebuilds that follow content, not dates.
#
# hc_content_stamp(<target> <stamp> <file>...) adds a target that runs on every build and
# rewrites <stamp> (a SHA-256 line per file) only when a file's content differs from what the
# stamp records. A custom command that lists <stamp> in its DEPENDS (and whose target depends
# on <target>) therefore reruns after any edit of one of the files, also an edit that leaves
# the file older than the command's outputs (`cp -p`, `rsync -t`, `tar x` of an older copy),
# and only then: an unchanged file costs one hash per build.
#
# Script mode, the work of that target:
#   cmake -DSTAMP=<stamp> -DLIST=<file with one path a line> -P content_stamp.cmake
if(CMAKE_SCRIPT_MODE_FILE)
  file(STRINGS "${LIST}" files)
  set(text "")
  foreach(f IN LISTS files)
    if(EXISTS "${f}")
      file(SHA256 "${f}" h)
    else()
      set(h "missing")
    endif()
    string(APPEND text "${h}  ${f}\n")
  endforeach()
  set(old "")
  if(EXISTS "${STAMP}")
    file(READ "${STAMP}" old)
  endif()
  if(NOT old STREQUAL text)
    # through a temporary: a stamp is whole or absent
    file(WRITE "${STAMP}.part" "${text}")
    file(RENAME "${STAMP}.part" "${STAMP}")
  endif()
  return()
endif()

set(HC_CONTENT_STAMP_SCRIPT ${CMAKE_CURRENT_LIST_FILE})

function(hc_content_stamp target stamp)
  set(list_file ${stamp}.files)
  string(REPLACE ";" "\n" lines "${ARGN}")
  file(WRITE ${list_file} "${lines}\n")
  add_custom_target(${target}
    COMMAND ${CMAKE_COMMAND} -DSTAMP=${stamp} -DLIST=${list_file} -P ${HC_CONTENT_STAMP_SCRIPT}
    BYPRODUCTS ${stamp}
    COMMENT "Hashing the sources of ${stamp}"
    VERBATIM)
endfunction()
