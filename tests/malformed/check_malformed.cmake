# Runs `kerf run SCENE` and passes when kerf exits 1 or 2 (not a crash), its
# message contains the text after "# expect:" on the scene's first line, and
# summary.json is written (status "error") exactly when the run had begun (exit 1).
file(STRINGS ${SCENE} first_line LIMIT_COUNT 1)
string(REGEX REPLACE "^# expect: *" "" expected "${first_line}")
if(expected STREQUAL first_line OR expected STREQUAL "")
  message(FATAL_ERROR "${SCENE}: the first line must be '# expect: TEXT'")
endif()
# What an earlier run left there (a summary) must not pass for this run's.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${KERF} run ${SCENE} --out ${OUT} --quiet
  RESULT_VARIABLE code ERROR_VARIABLE stderr OUTPUT_VARIABLE stdout TIMEOUT 120)
if(NOT code MATCHES "^[12]$")
  message(FATAL_ERROR "${SCENE}: expected exit code 1 or 2, got '${code}' (a crash?)\n${stderr}")
endif()
string(FIND "${stderr}" "${expected}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${SCENE}: the message does not mention '${expected}':\n${stderr}")
endif()
# Refused before any work (2): nothing written. Stopped in the run (1): the
# summary is there and says so.
if(code EQUAL 2 AND EXISTS ${OUT}/summary.json)
  message(FATAL_ERROR "${SCENE}: refused as a bad scene (exit 2) but ${OUT}/summary.json was written")
endif()
if(code EQUAL 1)
  if(NOT EXISTS ${OUT}/summary.json)
    message(FATAL_ERROR "${SCENE}: the run stopped (exit 1) without writing ${OUT}/summary.json")
  endif()
  file(READ ${OUT}/summary.json summary)
  if(NOT summary MATCHES "\"status\": \"error\"")
    message(FATAL_ERROR "${SCENE}: ${OUT}/summary.json does not say \"status\": \"error\"")
  endif()
endif()
message(STATUS "refused as expected: ${stderr}")
