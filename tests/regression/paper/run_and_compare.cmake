# Run one paper deck and compare its results file with the stored reference (see CMakeLists.txt).
file(REMOVE ${RESULTS})
# LAUNCHER (optional): a command prefix with '|' between its words, e.g. mpirun|-np|2.
string(REPLACE "|" ";" launcher "${LAUNCHER}")
execute_process(COMMAND ${launcher} ${COVCONTACT} run ${DECK} --output ${RESULTS} ${RUN_ARGS}
  RESULT_VARIABLE run_status)
if(NOT run_status EQUAL 0)
  message(FATAL_ERROR "covcontact run ${DECK} exited with ${run_status}")
endif()
execute_process(COMMAND ${COVCONTACT} compare ${RESULTS} ${REFERENCE}
  RESULT_VARIABLE compare_status)
if(NOT compare_status EQUAL 0)
  message(FATAL_ERROR "covcontact compare ${RESULTS} ${REFERENCE} exited with ${compare_status}")
endif()
