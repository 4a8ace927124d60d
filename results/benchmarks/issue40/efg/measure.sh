#!/bin/bash
# EFG against tet10 on the cantilever at equal accuracy (issue 40, item 4):
# wall time of whole `kerf run`s, each configuration three times, interleaved,
# nothing else running. Usage: [REPS=3] [NAMES="tet10_2.5mm ..."] measure.sh [kerf] > runs.txt (a kerf
# copied with its modules: LD_LIBRARY_PATH=its/modules).
# Reference tip (converged tet10, results/cost.md): -3.7662 mm.
K=${1:-build/cli/kerf}
S=scenes/cantilever.yaml
out=$(mktemp -d)
efg="--set discretization.method=efg"
gauss3="--set discretization.meshless.quadrature.order=3"
symmetric="--set discretization.meshless.quadrature.rule=symmetric"
gmsh_cells="--set discretization.meshless.background_cells=mesh"  # the cells before they were the lattice's
declare -A runs=(
  [tet10_3.33mm]="--set discretization.fem.size=0.00333"
  [tet10_2.5mm]="--set discretization.fem.size=0.0025"
  [efg_gauss3_2.5mm]="$efg $gauss3 --set discretization.meshless.spacing=0.0025"
  [efg_symmetric5_2.5mm]="$efg $symmetric --set discretization.meshless.spacing=0.0025"
  [efg_gauss3_2mm]="$efg $gauss3 --set discretization.meshless.spacing=0.002"
  [efg_symmetric5_2mm]="$efg $symmetric --set discretization.meshless.spacing=0.002"
  [efg_symmetric5_2.5mm_gmsh]="$efg $symmetric $gmsh_cells --set discretization.meshless.spacing=0.0025"
  [efg_symmetric5_2mm_gmsh]="$efg $symmetric $gmsh_cells --set discretization.meshless.spacing=0.002"
)
for rep in $(seq ${REPS:-3}); do
  for name in ${NAMES:-tet10_3.33mm tet10_2.5mm efg_gauss3_2.5mm efg_symmetric5_2.5mm efg_gauss3_2mm efg_symmetric5_2mm \
      efg_symmetric5_2.5mm_gmsh efg_symmetric5_2mm_gmsh}; do
    /usr/bin/time -f "%e" -o "$out/time" \
      $K run $S --set output.vtk=false --out "$out/$name" ${runs[$name]} > /dev/null 2>&1
    /usr/bin/python3 - "$out/$name/summary.json" "$(cat "$out/time")" "$name" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); p = d["timing"]["phases"]
tip = d["probes"]["tip"]["displacement"][2]
print(f"{sys.argv[3]:27s} wall {float(sys.argv[2]):6.2f} s  setup {p['setup_s']:5.2f}  assembly {p['assembly_s']:5.2f}"
      f"  factorize {p['factorize_s']:5.2f}  tip {tip * 1e3:.5f} mm  error {100 * (tip / -3.7662e-3 - 1):+.3f}%")
PY
  done
done
rm -rf "$out"
