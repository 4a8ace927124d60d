#!/bin/bash
# The static tet10 cantilever at 2.5 mm on gmsh's mesh and on kerf's lattice
# mesh (discretization.fem.box_mesher), three rounds interleaved, nothing else
# running. From the source tree, built:
#   results/benchmarks/issue40/close/tet10_fem_lattice.sh > results/benchmarks/issue40/close/tet10_fem_lattice.txt
# Reference tip (converged tet10, results/cost.md): -3.7662 mm.
out=$(mktemp -d)
for rep in 1 2 3; do
  for mesher in gmsh lattice; do
    /usr/bin/time -f "%e" -o "$out/time" build/cli/kerf run scenes/cantilever.yaml --quiet \
      --set discretization.fem.element=tet10 --set discretization.fem.size=0.0025 \
      --set discretization.fem.box_mesher=$mesher --set output.vtk=false --out "$out/$mesher" > /dev/null 2>&1
    /usr/bin/python3 - "$out/$mesher/summary.json" "$(cat "$out/time")" $mesher <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); p = d["timing"]["phases"]; tip = d["probes"]["tip"]["displacement"][2]
print(f"tet10_2.5mm_{sys.argv[3]:8s} wall {float(sys.argv[2]):5.2f} s  setup {p['setup_s']:5.2f}"
      f"  factorize {p['factorize_s']:5.2f}  nodes {d['counts']['nodes']}  tip {tip * 1e3:.5f} mm"
      f"  error {100 * (tip / -3.7662e-3 - 1):+.3f}%")
PY
  done
done
rm -rf "$out"
