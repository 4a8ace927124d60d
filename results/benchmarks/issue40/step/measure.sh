#!/bin/bash
# Issue 40, item 2 (the implicit corotational step): before and after,
# interleaved, one process at a time, nothing else running.
# "before" is kerf_benchmarks built at 5de96da (in build/, copied aside before
# this session's first change); "after" is this checkout's, built by `make build`.
#   results/benchmarks/issue40/step/measure.sh /path/to/before/kerf_benchmarks
before=${1:?the kerf_benchmarks built at 5de96da}
after=/work/main/build/tests/kerf_benchmarks
out=${2:-/tmp/measure_step}
mkdir -p $out
filter='BM_ImplicitEulerStepCorotationalCholmod/[012]|BM_ImplicitStepFloor/2|BM_StiffnessAssemblyCorotational/2'
filter+='|BM_ElementKernelsCorotational/2|BM_StiffnessAssemblyFloor/2|BM_CholmodSolve|BM_Triad/128'
for rep in 1 2 3; do
  for bin in before after; do
    [ $bin = before ] && exe=$before || exe=$after
    $exe --benchmark_filter="$filter" --benchmark_repetitions=1 \
      --benchmark_out=$out/step_${bin}_r${rep}.json --benchmark_out_format=json > $out/step_${bin}_r${rep}.txt 2>&1
  done
done
echo finished > $out/done
