#!/bin/bash
# Issue 40 at its close: every goal of the issue measured again at this
# build, one process at a time, nothing else running, each beside its floor
# from the same run. From the source tree, built (`make build`):
#   results/benchmarks/issue40/close/measure_all.sh [outdir]
# Writes one file a goal into outdir (default results/benchmarks/issue40/close):
#   startup.md  `kerf --version` and the 2D static scenes (floor: /bin/true), 21 runs each
#   calculix.txt  the static tet10 cantilever against CalculiX, 3 rounds (floor: the triad)
#   step_rN.txt  the implicit corotational step at 6 389 nodes and its floor, 3 rounds
#   cut_tT_rN.txt  one growth of the strip through the nodal block and its floor, 2 then 1 thread, 3 rounds
#   efg.txt  EFG against tet10 on the cantilever, 3 rounds
set -e
here=$(dirname "$0")
out=${1:-$here}
bench=build/tests/kerf_benchmarks
/usr/bin/python3 results/startup/startup.py build - 21 > "$out/startup.md"
results/benchmarks/issue40/calculix/measure.sh > "$out/calculix.txt" 2>&1
for rep in 1 2 3; do
  $bench --benchmark_filter='BM_ImplicitEulerStepCorotationalCholmod/3|BM_ImplicitStepFloor/3|BM_Triad/128' \
    --benchmark_repetitions=1 --benchmark_color=false > "$out/step_r$rep.txt" 2>&1
done
for threads in 2 1; do
  for rep in 1 2 3; do
    OMP_NUM_THREADS=$threads $bench --benchmark_filter='BM_MlsRowLinear|BM_CutUpdate/[01]/5/0|BM_CutUpdateFloor/436' \
      --benchmark_repetitions=1 --benchmark_color=false > "$out/cut_t${threads}_r$rep.txt" 2>&1
  done
done
REPS=3 NAMES="tet10_3.33mm tet10_2.5mm efg_symmetric5_2.5mm efg_symmetric5_2mm" \
  results/benchmarks/issue40/efg/measure.sh > "$out/efg.txt"
echo "$(git describe --always --dirty) $(date -u +%FT%TZ)" > "$out/done"
