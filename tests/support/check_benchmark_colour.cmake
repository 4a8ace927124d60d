# Fails if the benchmark report carries terminal colour codes into a file (a
# pipe here, not a terminal), or leaves them out when --benchmark_color=true
# asks for them: the report is a reporter of kerf's own, which Google
# Benchmark hands no colour setting.
#   cmake -DBENCHMARKS=kerf_benchmarks -P check_benchmark_colour.cmake
string(ASCII 27 escape)
foreach(colour auto true)
  execute_process(COMMAND ${BENCHMARKS} --benchmark_filter=BM_Triad/6 --benchmark_repetitions=1
                          --benchmark_min_time=0.01 --benchmark_color=${colour}
                  OUTPUT_VARIABLE report RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "${BENCHMARKS} --benchmark_filter=BM_Triad/6 failed")
  endif()
  string(FIND "${report}" "${escape}[" at)
  if(NOT report MATCHES "BM_Triad/6")
    message(SEND_ERROR "--benchmark_color=${colour}: the report names no BM_Triad/6 run:\n${report}")
  elseif(colour STREQUAL "auto" AND NOT at EQUAL -1)
    message(SEND_ERROR "--benchmark_color=auto, written to a pipe: the report holds colour codes")
  elseif(colour STREQUAL "true" AND at EQUAL -1)
    message(SEND_ERROR "--benchmark_color=true: the report holds no colour codes")
  endif()
endforeach()
