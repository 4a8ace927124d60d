#!/usr/bin/python3
"""Hyperelastic cases at the defaults (issue 35, item 6), every method, static,
against an independent reference. The law is kerf's `neohookean_uncoupled`,
which is CalculiX's `*HYPERELASTIC, NEO HOOKE`, so CalculiX (ccx, Debian's
calculix-ccx) solves the very same problem:
  sag          the soft block (4 x 2 x 2 cm, E = 3 kPa, nu = 0.45, clamped at
               x = 0) under its own weight: the corner (0.04, 0, 0) drops 2.7 cm
  compression  a 2 cm cube between glued platens squashed by 30%: the top's
               reaction force
  press        a rigid sphere (r = 5 mm) pushed 3 mm into a 4 x 4 x 2 cm block
               (frictionless): its contact force
Sag and compression: the reference is CalculiX C3D10 on a gmsh mesh at 1.67 mm;
kerf's tet10 on that same mesh file is reported beside it (the check that the
two codes solve the same problem). Press: ccx has no analytic rigid sphere;
the reference is kerf's tet10 at 2 mm (at 1.67 mm it ran past 30 minutes). Every method then runs the box
scene at its default size with no load steps, Newton settings or anything
else set by hand.
usage (source tree, idle machine; ccx installed), optionally naming cases:
    results/hyperelastic/hyperelastic.py build [case...] > results/hyperelastic/hyperelastic.csv"""
import json, os, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import calculix

build = sys.argv[1]
E, NU, RHO = 3.0e3, 0.45, 1000.0
material = f"material: {{model: neohookean_uncoupled, young: {E}, poisson: {NU}, density: {RHO}}}\n"
CASES = {
    "sag": dict(
        box=(0.04, 0.02, 0.02),
        scene="boundary:\n  - {select: {plane: {axis: x, at: 0}}, fix: [x, y, z]}\n"
              "body_force: {gravity: [0, 0, -9.81]}\n"
              "output: {vtk: false, probes: [{name: q, point: [0.04, 0, 0], field: displacement}]}\n",
        value=lambda s: s["probes"]["q"]["displacement"][2], quantity="corner z displacement (m)",
        ccx=dict(sets={"Nfix": lambda x: x[0] < 1e-9,
                       "Nq": lambda x: abs(x[0] - 0.04) < 1e-9 and x[1] < 1e-9 and x[2] < 1e-9},
                 boundary=["Nfix, 1, 3"], loads=["*DLOAD", "Eall, GRAV, 9.81, 0., 0., -1."], prints={"Nq": "U"},
                 value=lambda r: list(r["Nq"].values())[0][2])),
    "compression": dict(
        box=(0.02, 0.02, 0.02),
        scene="boundary:\n  - {select: {plane: {axis: z, at: 0}}, fix: [x, y, z]}\n"
              "  - {select: {plane: {axis: z, at: 0.02}}, displacement: [0, 0, -0.006]}\n"
              "output: {vtk: false, probes: [{name: q, select: {plane: {axis: z, at: 0.02}}, field: reaction}]}\n",
        value=lambda s: s["probes"]["q"]["reaction"][2], quantity="top reaction z (N)",
        ccx=dict(sets={"Nbottom": lambda x: x[2] < 1e-9, "Ntop": lambda x: abs(x[2] - 0.02) < 1e-9},
                 boundary=["Nbottom, 1, 3", "Ntop, 1, 2", "Ntop, 3, 3, -0.006"], loads=[], prints={"Ntop": "RF"},
                 value=lambda r: r["Ntop"][2])),
    "press": dict(
        box=(0.04, 0.04, 0.02),
        scene="boundary:\n  - {select: {plane: {axis: z, at: 0}}, fix: [x, y, z]}\n"
              "contact:\n  - {sphere: {center: [0.02, 0.02, 0.025], radius: 0.005}, displacement: [0, 0, -0.003]}\n"
              "output: {vtk: false, probes: [{name: q, contact: 0, field: contact_force}]}\n",
        value=lambda s: s["probes"]["q"]["contact_force"][2], quantity="contact force z (N)", ccx=None),
}
METHODS = [("tet4", []), ("tet4_averaged_nodal", ["discretization.fem.volumetric=averaged_nodal"]),
           ("tet10", ["discretization.fem.element=tet10"]), ("nodal", ["discretization.method=nodal"]),
           ("efg", ["discretization.method=efg"])]


def kerf(text, keys, folder):
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "scene.yaml")
    open(path, "w").write(text)
    command = [f"{build}/cli/kerf", "run", path, "--out", os.path.join(folder, "out"), "--quiet"]
    for k in keys:
        command += ["--set", k]
    subprocess.run(command, stderr=subprocess.DEVNULL)
    return json.load(open(os.path.join(folder, "out", "summary.json")))


def scene(case, name, mesh=None):
    """The case's scene on its box, or on a mesh file."""
    x, y, z = case["box"]
    domain = f"{{mesh: {mesh}}}" if mesh else f"{{box: {{min: [0, 0, 0], max: [{x}, {y}, {z}]}}}}"
    return (f"name: {name}\ndomain: {domain}\n" + material +
            "discretization: {method: fem}\nsolve: {analysis: static}\n" + case["scene"])


def row(case, method, summary, value, reference):
    v, t = summary.get("solver", {}), summary.get("timing", {})
    error = "" if value is None or reference is None else f"{value / reference - 1:+.4f}"
    print(",".join(str(x) for x in [case, method, summary.get("status"), summary.get("counts", {}).get("nodes"), value,
                                    reference, error, v.get("increments_taken"), v.get("cutbacks"),
                                    v.get("newton_iterations"), round(t.get("solve_s", 0), 2),
                                    '"' + summary.get("error", "")[:160].replace('"', "'") + '"']), flush=True)


chosen = sys.argv[2:] or list(CASES)
print("case,method,status,nodes,value,reference,relative_error,increments_taken,cutbacks,newton_iterations,solve_s,error")
for name, case in CASES.items():
    if name not in chosen:
        continue
    with tempfile.TemporaryDirectory() as work:
        if case["ccx"]:
            msh = calculix.box_mesh(case["box"], 0.001667, work)
            c = case["ccx"]
            reference = c["value"](calculix.run(msh, os.path.join(work, "ccx"), E, NU, RHO, c["sets"], c["boundary"],
                                                c["loads"], c["prints"]))
            s = kerf(scene(case, name, msh), [], os.path.join(work, "on_mesh"))
            print(f"{name},calculix_c3d10_1.67mm,ok,,{reference},{reference},+0.0000,,,,,\"\"", flush=True)
            row(name, "tet10_same_mesh_as_calculix", s, case["value"](s) if s["status"] == "ok" else None, reference)
        else:
            s = kerf(scene(case, name), ["discretization.fem.element=tet10", "discretization.fem.size=0.002"],
                     os.path.join(work, "reference"))
            reference = case["value"](s) if s["status"] == "ok" else None
            row(name, "tet10_2mm_reference", s, reference, reference)
        for method, keys in METHODS:
            s = kerf(scene(case, name), keys, os.path.join(work, method))
            row(name, method, s, case["value"](s) if s["status"] == "ok" else None, reference)
