# Runs `kerf run SCENE` and passes when kerf exits 1 or 2 (not a crash) and its
# message contains the text after "# expect:" on the scene's first line.
file(STRINGS ${SCENE} first_line LIMIT_COUNT 1)
string(REGEX REPLACE "^# expect: *" "" expected "${first_line}")
if(expected STREQUAL first_line OR expected STREQUAL "")
  message(FATAL_ERROR "${SCENE}: the first line must be '# expect: TEXT'")
endif()
execute_process(COMMAND ${KERF} run ${SCENE} --out ${OUT} --quiet
  RESULT_VARIABLE code ERROR_VARIABLE stderr OUTPUT_VARIABLE stdout TIMEOUT 120)
if(NOT code MATCHES "^[12]$")
  message(FATAL_ERROR "${SCENE}: expected exit code 1 or 2, got '${code}' (a crash?)\n${stderr}")
endif()
string(FIND "${stderr}" "${expected}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${SCENE}: the message does not mention '${expected}':\n${stderr}")
endif()
message(STATUS "refused as expected: ${stderr}")
