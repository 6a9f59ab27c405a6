# golden_changed.cmake: copies the golden files, changes one read of one file, and expects
# `harris-cosim golden --check` on the copy to exit 1 naming that file and line.
file(REMOVE_RECURSE ${WORK})
file(COPY ${GOLDEN}/ DESTINATION ${WORK})
file(READ ${WORK}/reads_flat_40x30.csv text)
string(REGEX REPLACE "\n([0-9]+,[0-9]+,[0-9]+,[0-9]+),([0-9]+)\n" "\n\\1,99999\n" changed "${text}")
if(changed STREQUAL text)
  message(FATAL_ERROR "no read row to change in reads_flat_40x30.csv")
endif()
file(WRITE ${WORK}/reads_flat_40x30.csv "${changed}")
execute_process(COMMAND ${EXPECT} 1 "reads_flat_40x30.csv:[0-9]+: golden '.*' but the model gives" --
                        ${CLI} golden --out ${WORK} --check
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "golden --check did not report the changed file as a mismatch")
endif()
