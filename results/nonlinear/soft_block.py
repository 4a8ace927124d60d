#!/usr/bin/python3
"""The soft block of issue 35 sagging under its own weight (about 2.8 cm at the
tip of a 4 cm block: large deformation), static at the defaults (no load
steps, no Newton settings), every method; then implicit Euler at dt = 10 ms
for 0.5 s. The reference is tet10 at 1.67 mm. usage (source tree, idle machine):
    results/nonlinear/soft_block.py build > results/nonlinear/soft_block.csv"""
import json, os, subprocess, sys, tempfile

build, here = sys.argv[1], os.path.dirname(os.path.abspath(__file__))
cases = [("tet4", ["discretization.fem.element=tet4"]), ("tet10", ["discretization.fem.element=tet10"]),
         ("tet4_averaged_nodal", ["discretization.fem.volumetric=averaged_nodal"]),
         ("nodal", ["discretization.method=nodal", "solve.analysis=static"]), ("efg", ["discretization.method=efg"]),
         ("tet10_1.67mm", ["discretization.fem.element=tet10", "discretization.fem.size=0.001667"])]
implicit = ["solve.analysis=dynamic", "solve.integrator=implicit-euler", "solve.dt=0.01", "solve.duration=0.5"]
runs = [(name, "static", keys) for name, keys in cases] + \
       [(name, "implicit", keys + implicit) for name, keys in cases if name in ("tet4", "tet10", "tet4_averaged_nodal", "nodal")]
print("method,analysis,status,nodes,tip_z_m,increments_taken,cutbacks,newton_iterations,definite_tangent_fallbacks,"
      "converged_by_step,solve_s,error")
for name, analysis, keys in runs:
    with tempfile.TemporaryDirectory() as out:
        command = [f"{build}/cli/kerf", "run", f"{here}/soft_block.yaml", "--out", out, "--quiet"]
        for k in keys:
            command += ["--set", k]
        subprocess.run(command, stderr=subprocess.DEVNULL)
        s = json.load(open(f"{out}/summary.json"))
    v = s.get("solver", {})
    tip = s.get("probes", {}).get("tip", {}).get("displacement", [None] * 3)[2]
    print(",".join(str(x) for x in [name, analysis, s["status"], s.get("counts", {}).get("nodes"), tip,
                                    v.get("increments_taken"), v.get("cutbacks"), v.get("newton_iterations"),
                                    v.get("definite_tangent_fallbacks"), v.get("newton_converged_by", {}).get("step"),
                                    round(s.get("timing", {}).get("solve_s", 0), 2),
                                    '"' + s.get("error", "")[:200].replace('"', "'") + '"']), flush=True)
