#!/bin/bash
# Issue 40, item 3 (one growth of the strip through the 5 832-node nodal
# block): before and after, interleaved, one process at a time, nothing else
# running, 2 threads then 1.
# "before" is kerf_benchmarks built at d56991f (copied aside before this
# session's first change); "after" is this checkout's, built by `make build`.
#   results/benchmarks/issue40/cut/measure.sh /path/to/before/kerf_benchmarks [outdir]
before=${1:?the kerf_benchmarks built at d56991f}
after=/work/main/build/tests/kerf_benchmarks
out=${2:-/tmp/measure_cut}
mkdir -p $out
filter='BM_MlsRowLinear|BM_CutUpdate/[01]/5/0|BM_CutUpdateFloor/436'
for threads in 2 1; do
  for rep in 1 2 3 4; do
    for bin in before after; do
      [ $bin = before ] && exe=$before || exe=$after
      OMP_NUM_THREADS=$threads $exe --benchmark_filter="$filter" --benchmark_repetitions=1 \
        > $out/cut_${bin}_t${threads}_r${rep}.txt 2>&1
    done
  done
done
echo finished > $out/done
