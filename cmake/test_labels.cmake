# Every ctest test gets a label, the kind its name starts with (unit,
# regression, study, mpi, ...: `ctest -L mpi`, `ctest -LE study`), and a
# timeout for its kind unless it sets its own. The timeouts are about ten
# times the longest test of each kind measured on the 2-core VM (2026-11-28:
# unit 6 s, regression 37 s, study 58 s, mpi 31 s, paraview 51 s), so a
# slower machine passes and a hung test fails in minutes, not at CI's limit.
set(KERF_TEST_TIMEOUTS unit=120 convergence=120 malformed=120 scene_check=120 regression=600 study=900 mpi=600)
set(KERF_TEST_TIMEOUT_OTHER 600)

# The timeout (s) for tests of `kind`.
function(kerf_test_timeout kind out)
  set(timeout ${KERF_TEST_TIMEOUT_OTHER})
  foreach(pair ${KERF_TEST_TIMEOUTS})
    if(pair MATCHES "^${kind}=([0-9]+)$")
      set(timeout ${CMAKE_MATCH_1})
    endif()
  endforeach()
  set(${out} ${timeout} PARENT_SCOPE)
endfunction()

# Labels and timeouts for the tests the calling directory added (CMake 3.25
# sets test properties only from the directory that added the test).
function(kerf_label_tests)
  get_property(tests DIRECTORY PROPERTY TESTS)
  foreach(test ${tests})
    string(REGEX REPLACE "\\..*$" "" kind "${test}")
    set_tests_properties(${test} PROPERTIES LABELS ${kind})
    get_test_property(${test} TIMEOUT own)
    if(NOT own)
      kerf_test_timeout(${kind} timeout)
      set_tests_properties(${test} PROPERTIES TIMEOUT ${timeout})
    endif()
  endforeach()
endfunction()
