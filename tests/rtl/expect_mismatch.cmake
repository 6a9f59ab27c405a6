# expect_mismatch.cmake: the test of the test. Runs an entity bench with STAGE_FLIP_VECTOR
# set, so that the C++ side expects a wrong bit 0 at one vector of a correct entity, and
# checks that the bench fails the way a real mismatch fails: exit status 1, one value
# mismatch in the summary, and a message naming the entity, the vector (with its extreme or
# random number), its inputs, the expected and the actual value.
#   cmake -DCMD=<command, '|'-separated> -DFLIP=<vector> -DENTITY=<stem>
#         [-DDETAIL=<regex the message must also match>] -P expect_mismatch.cmake
string(REPLACE "|" ";" cmd "${CMD}")
set(ENV{STAGE_FLIP_VECTOR} "${FLIP}")
execute_process(COMMAND ${cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(log "${out}${err}")
message("${log}")
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "exit status ${rc}; a bench with a mismatch must exit with 1")
endif()
set(head "${ENTITY}: MISMATCH at cycle [0-9]+ \\([^)]*\\): vector ${FLIP} \\((extreme|random) #[0-9]+\\): ")
foreach(re IN ITEMS "${head}" "${DETAIL}" "mismatches: 1 value, 0 metavalue")
  if(NOT log MATCHES "${re}")
    message(FATAL_ERROR "the output does not match: ${re}")
  endif()
endforeach()
