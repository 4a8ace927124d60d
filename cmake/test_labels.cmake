# Every ctest test gets a label, the kind its name starts with (unit,
# regression, study, mpi, ...: `ctest -L mpi`, `ctest -LE study`), and a
# timeout for its kind unless it sets its own. The timeouts are about ten
# times the longest test of each kind measured on the 2-core VM (2026-11-28:
# unit 6 s, regression 37 s, study 58 s, mpi 31 s, paraview 51 s), so a
# slower machine passes and a hung test fails in minutes, not at CI's limit.
set(KERF_TEST_TIMEOUTS unit=120 convergence=120 malformed=120 scene_check=120 regression=600 study=900 mpi=600)
set(KERF_TEST_TIMEOUT_OTHER 600)
include(${CMAKE_CURRENT_LIST_DIR}/slow_tests.cmake)

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

# The discovered GoogleTest tests among KERF_SLOW_GTESTS get the slow label
# at ctest time (they do not exist before): the calling directory includes
# this file after its gtest_discover_tests calls.
function(kerf_label_discovered_slow_tests)
  set(file ${CMAKE_CURRENT_BINARY_DIR}/kerf_slow_gtests.cmake)
  file(WRITE ${file} "set(KERF_LABEL_DISCOVERED_SLOW_TESTS ON)\ninclude(${PROJECT_SOURCE_DIR}/cmake/slow_tests.cmake)\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${file})
endfunction()

# Labels and timeouts for the tests the calling directory added (CMake 3.25
# sets test properties only from the directory that added the test).
function(kerf_label_tests)
  get_property(tests DIRECTORY PROPERTY TESTS)
  foreach(test ${tests})
    string(REGEX REPLACE "\\..*$" "" kind "${test}")
    set(labels ${kind})
    if(test IN_LIST KERF_SLOW_TESTS)
      list(APPEND labels slow)
    endif()
    set_tests_properties(${test} PROPERTIES LABELS "${labels}")
    # An MPI test runs several processes: ctest must not run others beside it
    # as if it were one (a rank count it does not declare is refused here).
    get_test_property(${test} PROCESSORS processors)
    if(kind STREQUAL "mpi" AND NOT processors)
      message(FATAL_ERROR "test ${test}: an MPI test must declare PROCESSORS, the most ranks it runs at once")
    endif()
    get_test_property(${test} TIMEOUT own)
    if(NOT own)
      kerf_test_timeout(${kind} timeout)
      set_tests_properties(${test} PROPERTIES TIMEOUT ${timeout})
    endif()
  endforeach()
endfunction()
