#!/usr/bin/python3
"""kerf loads gmsh, PETSc (with MPI) and VTK only when a run needs them
(core/module_loader.h): the program links none of them, and each run's
summary.json lists the modules it loaded (timing.modules).
usage: modules_on_demand.py KERF SCENES_DIR OUT"""
import json, os, shutil, subprocess, sys

kerf, scenes, out = sys.argv[1:4]
here = os.path.dirname(os.path.abspath(__file__))
hanging, pulled = f"{here}/plate_gravity_2d.yaml", f"{scenes}/plate_tension_2d.yaml"
shutil.rmtree(out, ignore_errors=True)
failures = []

linked = subprocess.run(["ldd", kerf], capture_output=True, text=True, check=True).stdout
for heavy in ("libgmsh", "libpetsc", "libmpi", "libvtk"):
    if heavy in linked:
        failures.append(f"{kerf} links {heavy} at its start (ldd): it should load it on demand")

cases = [  # the scene, what the run asks, and the modules it must have loaded
    ("nodal_lattice", hanging, [], set()),  # no mesh: no boundary load, no contact
    ("nodal_lattice_paraview", hanging, ["output.vtk=true"], {"vtk"}),
    # a lattice's boundary cells are its own (meshless.background_cells: auto); gmsh meshes them when asked
    ("nodal_traction", pulled, ["discretization.method=nodal", "output.vtk=false"], set()),
    ("nodal_traction_gmsh_cells", pulled,
     ["discretization.method=nodal", "discretization.meshless.background_cells=mesh", "output.vtk=false"], {"gmsh"}),
    ("efg", pulled, ["discretization.method=efg", "output.vtk=false"], set()),
    ("fem", pulled, ["output.vtk=false"], {"gmsh"}),
    ("fem_lattice", pulled, ["output.vtk=false", "discretization.fem.box_mesher=lattice"], set()),  # kerf's own cells
    ("fem_mesh_file", f"{scenes}/cube_from_mesh.yaml", ["output.vtk=false"], set()),  # MSH 4.1, read by kerf itself
    ("fem_petsc", pulled, ["output.vtk=false", "solve.linear_solver=petsc"], {"gmsh", "petsc"}),
]
for name, scene, keys, expected in cases:
    command = [kerf, "run", scene, "--quiet", "--out", f"{out}/{name}"]
    for k in keys:
        command += ["--set", k]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        failures.append(f"{name}: kerf failed: {done.stderr}")
        continue
    summary = json.load(open(f"{out}/{name}/summary.json"))
    modules = summary["timing"]["modules"]
    if set(modules) != expected:
        failures.append(f"{name}: loaded {sorted(modules)}; expected {sorted(expected)}")
    for module, cost in modules.items():
        if not (cost["load_ms"] > 0 and cost["libraries"] >= 1):
            failures.append(f"{name}: module {module} recorded as {cost}")
    print(f"{name}: modules {json.dumps(modules)}")

if failures:
    sys.exit("\n".join(failures))
print("each module loaded only by the runs that need it")
