# Runs COMMAND; passes when its exit code is EXPECTED_EXIT and its output matches REGEX within
# TIMEOUT seconds (default 120).
if(NOT DEFINED TIMEOUT)
  set(TIMEOUT 120)
endif()
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT ${TIMEOUT})
set(all "${out}${err}")
string(REPLACE "\n" " " flat "${all}")
if(NOT rc STREQUAL "${EXPECTED_EXIT}")
  message(FATAL_ERROR "exit code ${rc}, expected ${EXPECTED_EXIT}; output:\n${all}")
endif()
if(NOT flat MATCHES "${REGEX}")
  message(FATAL_ERROR "output does not match '${REGEX}':\n${all}")
endif()
