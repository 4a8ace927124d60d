#!/bin/bash
# Issue 40, items 3 and 4: before and after, interleaved, one process at a time,
# nothing else running. "before" is commit 61c2b09 in a worktree:
#   git worktree add /tmp/before 61c2b09 && cd /tmp/before &&
#   cmake -S . -B build -DCMAKE_BUILD_TYPE=Release &&
#   cmake --build build -j2 --target kerf_benchmarks kerf kerf_modules
# "after" is this checkout at /work/main, built by `make build`. Outputs in
# /tmp/measure (copied to results/benchmarks/issue40/).
out=/tmp/measure
for rep in 1 2; do
  for bin in before after; do
    root=/work/main; [ $bin = before ] && root=/tmp/before
    for t in 1 2; do
      OMP_NUM_THREADS=$t $root/build/tests/kerf_benchmarks --benchmark_filter='BM_CutUpdate/[01]/5/0|BM_CutUpdateFloor/436' \
        --benchmark_repetitions=1 --benchmark_out=$out/cut_${bin}_t${t}_r${rep}.json --benchmark_out_format=json > $out/cut_${bin}_t${t}_r${rep}.txt 2>&1
    done
  done
done
for rep in 1 2; do
  for bin in before after; do
    root=/work/main; [ $bin = before ] && root=/tmp/before
    /usr/bin/time -f "%e s %M KB" -o $out/efg_${bin}_r${rep}.time $root/build/cli/kerf run /work/main/scenes/cantilever.yaml --set discretization.method=efg --set discretization.meshless.spacing=0.0025 --set discretization.meshless.quadrature.order=3 --set output.vtk=false --out $out/efg_${bin}_r${rep} > /dev/null 2>&1
    /usr/bin/time -f "%e s %M KB" -o $out/tet10_${bin}_r${rep}.time $root/build/cli/kerf run /work/main/scenes/cantilever.yaml --set discretization.fem.size=0.0025 --set output.vtk=false --out $out/tet10_${bin}_r${rep} > /dev/null 2>&1
  done
done
echo finished > $out/done
