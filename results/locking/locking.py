#!/usr/bin/python3
"""Locking: the soft block of issue 35 (results/nonlinear/soft_block.yaml)
with a linear material at nu = 0.3 (no locking: the elements' own bending
error), 0.45, 0.49, 0.499, static, every method at the default size, against
tet10 at 1.67 mm; tet4 with its bulk term averaged at the nodes
(fem.volumetric: averaged_nodal) also at 1.67 and 1.25 mm, and plain tet4 at
1.25 mm, to show which converges.
usage (source tree, idle machine): results/locking/locking.py build > results/locking/locking.csv"""
import json, os, subprocess, sys, tempfile

build, here = sys.argv[1], os.path.dirname(os.path.abspath(__file__))
methods = [("tet4", ["discretization.fem.element=tet4"]), ("tet10", ["discretization.fem.element=tet10"]),
           ("nodal", ["discretization.method=nodal", "solve.analysis=static"]), ("efg", ["discretization.method=efg"]),
           ("tet4_averaged_nodal", ["discretization.fem.volumetric=averaged_nodal"]),
           ("tet4_averaged_nodal_1.67mm", ["discretization.fem.volumetric=averaged_nodal", "discretization.fem.size=0.001667"]),
           ("tet4_averaged_nodal_1.25mm", ["discretization.fem.volumetric=averaged_nodal", "discretization.fem.size=0.00125"]),
           ("tet4_1.25mm", ["discretization.fem.size=0.00125"]),
           ("reference", ["discretization.fem.element=tet10", "discretization.fem.size=0.001667"])]


def tip(keys):
    with tempfile.TemporaryDirectory() as out:
        command = [f"{build}/cli/kerf", "run", f"{here}/../nonlinear/soft_block.yaml", "--out", out, "--quiet",
                   "--set", "material.model=linear"]
        for k in keys:
            command += ["--set", k]
        subprocess.run(command, stderr=subprocess.DEVNULL)
        s = json.load(open(f"{out}/summary.json"))
    return s["probes"]["tip"]["displacement"][2], s["counts"]["nodes"]


print("nu,method,nodes,tip_z_m,fraction_of_reference")
for nu in ("0.3", "0.45", "0.49", "0.499"):
    results = {name: tip(keys + [f"material.poisson={nu}"]) for name, keys in methods}
    reference = results["reference"][0]
    for name, (z, nodes) in results.items():
        print(f"{nu},{name},{nodes},{z},{z / reference:.4f}", flush=True)
