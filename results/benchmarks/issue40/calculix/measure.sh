#!/bin/bash
# kerf's static tet10 cantilever against CalculiX (Debian's ccx, SPOOLES, two
# threads) on the same second-order gmsh mesh, 2.5 mm (about 20 800 nodes):
# wall times of whole runs, each configuration three times, interleaved,
# nothing else running; then the machine's memory bandwidth (BM_Triad), the
# floor of p_multigrid's solve, which streams the matrix about
# 5 times a CG iteration (the CG product, two Chebyshev steps before and after
# the coarse correction, its residual) plus 12 times for the Lanczos estimate.
# Usage (from the source tree, built): results/benchmarks/issue40/calculix/measure.sh > runs.txt
# A second argument, another build's kerf, adds its msh p_multigrid run to
# each round ("before_msh_p_multigrid").
K=${1:-build/cli/kerf}
BEFORE=${2:-}
here=$(dirname "$0")
work=$(mktemp -d)
cat > "$work/box.geo" <<GEO
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.1, 0.02, 0.02};
Mesh.CharacteristicLengthMax = 0.0025;
Mesh.ElementOrder = 2;
Mesh.SecondOrderLinear = 1;
Mesh.MshFileVersion = 2.2;
GEO
gmsh -3 "$work/box.geo" -o "$work/box.msh" > /dev/null
/usr/bin/python3 "$here/cantilever_inp.py" "$work/box.msh" "$work/model.inp"
sed "s|^  box: .*|  mesh: $work/box.msh|" scenes/cantilever.yaml > "$work/cantilever_msh.yaml"
echo "mesh: $(sed -n '/\$Nodes/{n;p;q}' "$work/box.msh") nodes; kerf $(git describe --always --dirty 2>/dev/null)"
declare -A runs=(
  [kerf_box_cholmod]="scenes/cantilever.yaml --set discretization.fem.size=0.0025"
  [kerf_box_p_multigrid]="scenes/cantilever.yaml --set discretization.fem.size=0.0025 --set solve.linear_solver=p_multigrid"
  [kerf_msh_cholmod]="$work/cantilever_msh.yaml"
  [kerf_msh_p_multigrid]="$work/cantilever_msh.yaml --set solve.linear_solver=p_multigrid"
  [before_msh_p_multigrid]="$work/cantilever_msh.yaml --set solve.linear_solver=p_multigrid"
)
for rep in 1 2 3; do
  (cd "$work" && OMP_NUM_THREADS=2 CCX_NPROC_EQUATION_SOLVER=2 /usr/bin/time -f "%e" -o ccx.time ccx -i model > ccx.log 2>&1)
  tip=$(awk '/displacements/{getline; getline; print $4}' "$work/model.dat")
  printf "%-22s wall %6.2f s  tip %.5f mm\n" ccx "$(cat "$work/ccx.time")" "$(/usr/bin/python3 -c "print($tip * 1e3)")"
  names="kerf_box_cholmod kerf_box_p_multigrid kerf_msh_cholmod kerf_msh_p_multigrid"
  [ -n "$BEFORE" ] && names+=" before_msh_p_multigrid"
  for name in $names; do
    binary=$K
    [ $name = before_msh_p_multigrid ] && binary=$BEFORE
    /usr/bin/time -f "%e" -o "$work/time" $binary run ${runs[$name]} --set output.vtk=false --out "$work/$name" \
      > /dev/null 2>&1
    /usr/bin/python3 - "$work/$name/summary.json" "$(cat "$work/time")" "$name" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); p = d["timing"]["phases"]
tip = d["probes"]["tip"]["displacement"][2]
print(f"{sys.argv[3]:22s} wall {float(sys.argv[2]):6.2f} s  tip {tip * 1e3:.5f} mm  setup {p['setup_s']:5.2f}"
      f"  assembly {p['assembly_s']:5.2f}  factorize {p['factorize_s']:5.2f}  solve {p['solve_s']:5.2f}"
      f"  iterations {d['solver']['linear_iterations']}  nonzeros (estimate) {d['estimate']['nonzeros']:.3g}")
PY
  done
done
build/tests/kerf_benchmarks --benchmark_filter='BM_Triad/128' 2>&1 | sed 's/\x1b\[[0-9;]*m//g' | grep "triad bandwidth"
rm -rf "$work"
