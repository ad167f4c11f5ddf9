# cmake -DPROGRAM=<exe> -DEXPECTED=<file> -P CompareOutput.cmake: runs PROGRAM and fails unless it exits 0
# and its standard output equals the contents of EXPECTED exactly.
execute_process(COMMAND ${PROGRAM} OUTPUT_VARIABLE _actual RESULT_VARIABLE _status)
file(READ ${EXPECTED} _expected)
if(NOT _status EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} exited with ${_status}; it printed:\n${_actual}")
endif()
if(NOT _actual STREQUAL _expected)
  message(FATAL_ERROR "${PROGRAM} printed:\n${_actual}\nREADME.md says it prints:\n${_expected}")
endif()
message(STATUS "output matches README.md:\n${_actual}")
