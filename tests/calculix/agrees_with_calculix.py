#!/usr/bin/python3
"""kerf's tet10 and CalculiX's C3D10 (Debian's calculix-ccx) on the same gmsh
mesh, with the same law (kerf's neohookean_uncoupled is ccx's NEO HOOKE):
a block sagging 2.7 cm under its own weight and a cube squashed by 30%
between glued platens, static, large deformation, 5 mm cells. They must
agree to 1e-4 (measured at 5 mm: 1.7e-5 and 3.3e-6; at 2.5 mm 8e-6, at
1.67 mm 2e-8, so the rest shrinks with the mesh; the coupled neo-Hookean
law instead differs by more than 1e-2).
usage: agrees_with_calculix.py KERF WORKDIR"""
import json, os, subprocess, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "results", "hyperelastic"))
import calculix

kerf, work = sys.argv[1], sys.argv[2]
E, NU, RHO = 3.0e3, 0.45, 1000.0


def run_kerf(name, msh, rest):
    scene = os.path.join(work, name + ".yaml")
    open(scene, "w").write(f"name: {name}\ndomain: {{mesh: {msh}}}\n"
                           f"material: {{model: neohookean_uncoupled, young: {E}, poisson: {NU}, density: {RHO}}}\n"
                           "discretization: {method: fem, fem: {element: tet10}}\nsolve: {analysis: static}\n" + rest)
    out = os.path.join(work, name + "_out")
    subprocess.run([kerf, "run", scene, "--out", out, "--quiet"], check=True)
    return json.load(open(os.path.join(out, "summary.json")))


def agree(what, ours, theirs, scale):
    error = max(abs(a - b) for a, b in zip(ours, theirs)) / scale
    print(f"{what}: kerf {ours}, ccx {theirs}, difference {error:.2e} of {scale:.4g}")
    return error < 1e-4


os.makedirs(work, exist_ok=True)
ok = True
msh = calculix.box_mesh((0.04, 0.02, 0.02), 0.005, work, "sag")
corner = lambda x: abs(x[0] - 0.04) < 1e-9 and x[1] < 1e-9 and x[2] < 1e-9
theirs = calculix.run(msh, os.path.join(work, "sag_ccx"), E, NU, RHO, {"Nfix": lambda x: x[0] < 1e-9, "Nq": corner},
                      ["Nfix, 1, 3"], ["*DLOAD", "Eall, GRAV, 9.81, 0., 0., -1."], {"Nq": "U"})
ours = run_kerf("sag", msh, "boundary:\n  - {select: {plane: {axis: x, at: 0}}, fix: [x, y, z]}\n"
                "body_force: {gravity: [0, 0, -9.81]}\n"
                "output: {vtk: false, probes: [{name: q, point: [0.04, 0, 0], field: displacement}]}\n")
u = list(theirs["Nq"].values())[0]
ok &= agree("sag corner displacement (m)", ours["probes"]["q"]["displacement"], u, abs(u[2]))
ok &= abs(u[2]) > 0.02  # large deformation, or the comparison proves little

msh = calculix.box_mesh((0.02, 0.02, 0.02), 0.005, work, "compression")
theirs = calculix.run(msh, os.path.join(work, "compression_ccx"), E, NU, RHO,
                      {"Nbottom": lambda x: x[2] < 1e-9, "Ntop": lambda x: abs(x[2] - 0.02) < 1e-9},
                      ["Nbottom, 1, 3", "Ntop, 1, 2", "Ntop, 3, 3, -0.006"], [], {"Ntop": "RF"})
ours = run_kerf("compression", msh, "boundary:\n  - {select: {plane: {axis: z, at: 0}}, fix: [x, y, z]}\n"
                "  - {select: {plane: {axis: z, at: 0.02}}, displacement: [0, 0, -0.006]}\n"
                "output: {vtk: false, probes: [{name: q, select: {plane: {axis: z, at: 0.02}}, field: reaction}]}\n")
ok &= agree("top reaction (N)", ours["probes"]["q"]["reaction"], theirs["Ntop"], abs(theirs["Ntop"][2]))
sys.exit(0 if ok else 1)
