#!/usr/bin/python3
"""Start-up: the wall time of whole `kerf` processes from a cold start of the
process (page cache warm), beside the floor of starting any process
(/bin/true) measured in the same run, and "before": kerf as it was before issue 40
(BEFORE_BUILD, a build of commit b2674c3), linking gmsh, PETSc and MPI, and
VTK's IOXML at its start; or any other build to compare with (84b08a3: gmsh
read every .msh file, before kerf's own reader).
2D static plates of about 1,000 nodes: one hanging under its weight by
nodal integration on a lattice (tests/startup/plate_gravity_2d.yaml: no
mesh, nothing but CHOLMOD), with and without ParaView output; and
scenes/plate_tension_2d.yaml, pulled on an edge, by FEM tri6 and by nodal
integration (gmsh meshes the box: FEM's cells, the nodal body's boundary
cells that carry the traction); the same FEM plate and a 3D organ (tet4,
the organ study's .geo at 3 mm: 2,147 nodes), read from .msh files that
gmsh makes here first (kerf reads MSH 4.1 itself). Each process is run
`repeats` times, one at a time; median and min. The modules each run loaded, and what
loading them cost, are read from its summary.json (timing.modules).
usage (source tree, idle machine):
  git worktree add /tmp/before b2674c3 && cmake -S /tmp/before -B /tmp/before/build && \
  cmake --build /tmp/before/build --target kerf -j 2
  results/startup/startup.py build /tmp/before/build [repeats] > results/startup/startup.md
  results/startup/startup.py build - [repeats]: this build alone (the "before" column left empty)
(startup_84b08a3.md: the same with /tmp/before84 at 84b08a3.)"""
import json, os, statistics, subprocess, sys, tempfile, time

build = sys.argv[1]
before_build = sys.argv[2] if len(sys.argv) > 2 and sys.argv[2] != "-" else None  # "-": this build alone
repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 21
here = os.path.dirname(os.path.abspath(__file__))
kerf = f"{build}/cli/kerf"
kerf_before = f"{before_build}/cli/kerf" if before_build else None
plate = f"{here}/../../scenes/plate_tension_2d.yaml"
hanging = f"{here}/../../tests/startup/plate_gravity_2d.yaml"
meshes = tempfile.mkdtemp()


def scene_on_mesh_file(scene, geo, options, name):
    """`scene` with its domain read from the .msh file gmsh makes of `geo` (written in `meshes`)."""
    with open(f"{meshes}/{name}.geo", "w") as f:
        f.write(geo)
    subprocess.run(["gmsh", f"{meshes}/{name}.geo", "-format", "msh41", "-o", f"{meshes}/{name}.msh"] + options,
                   check=True, stdout=subprocess.DEVNULL)
    text = open(scene).read()
    start = text.index("domain:\n")  # "domain:" and one line under it, box or mesh
    end = text.index("\n", text.index("\n", start) + 1) + 1
    with open(f"{meshes}/{name}.yaml", "w") as f:
        f.write(text[:start] + f"domain: {{mesh: {meshes}/{name}.msh}}\n" + text[end:])
    return f"{meshes}/{name}.yaml"


plate_file = scene_on_mesh_file(plate, "SetFactory(\"OpenCASCADE\");\nRectangle(1) = {0, 0, 0, 0.1, 0.05};\n",
                                ["-2", "-order", "2", "-clmax", "0.0045"], "plate")
organ_geo = open(f"{here}/../../scenes/meshes/organ.geo").read()
organ_file = scene_on_mesh_file(f"{here}/../../scenes/organ_sag.yaml", organ_geo, ["-3", "-clmax", "0.003"], "organ")
nodal = ["--set", "discretization.method=nodal", "--set", "discretization.meshless.spacing=0.0022"]
fem = ["--set", "discretization.fem.size=0.0045"]
no_vtk = ["--set", "output.vtk=false"]
cases = [
    ("floor: /bin/true", ["/bin/true"], False),
    ("kerf --version", [kerf, "--version"], False),
    ("kerf check (the plate)", [kerf, "check", plate], False),
    ("2D static nodal, hanging, no output but probes", [kerf, "run", hanging, "--quiet"], True),
    ("2D static nodal, hanging, ParaView output", [kerf, "run", hanging, "--quiet", "--set", "output.vtk=true"], True),
    ("2D static nodal, pulled (its boundary cells: the lattice's)", [kerf, "run", plate, "--quiet"] + nodal + no_vtk, True),
    ("2D static FEM tri6, pulled (gmsh meshes the box)", [kerf, "run", plate, "--quiet"] + fem + no_vtk, True),
    ("2D static FEM tri6, pulled, fem.box_mesher: lattice", [kerf, "run", plate, "--quiet", "--set",
                                                             "discretization.fem.box_mesher=lattice"] + fem + no_vtk,
     True),
    ("2D static FEM tri6, pulled, the plate's .msh file", [kerf, "run", plate_file, "--quiet"] + no_vtk, True),
    ("3D static FEM tet4, the organ's .msh file", [kerf, "run", organ_file, "--quiet", "--set",
                                                   "discretization.method=fem"] + no_vtk, True),
]


def wall(command, environment, out):
    start = time.perf_counter()
    done = subprocess.run(command + (["--out", out] if out else []), env=environment, stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, text=True)
    took = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} failed: {done.stderr}")
    return took


def measure(command, runs):
    environment = dict(os.environ, OMP_NUM_THREADS="1")
    with tempfile.TemporaryDirectory() as out:
        times = [wall(command, environment, out if runs else None) for _ in range(repeats)]
        summary = json.load(open(f"{out}/summary.json")) if runs else None
    return times, summary


print("| process | now: median (min) ms | before: median (min) ms | nodes | modules loaded: ms (libraries) |")
print("|---|---|---|---|---|")
for label, command, runs in cases:
    now, summary = measure(command, runs)
    before, _ = measure([kerf_before] + command[1:], runs) if kerf_before and command[0] == kerf else (None, None)
    nodes = summary["counts"]["nodes"] if summary else ""
    modules = ", ".join(f"{name} {m['load_ms']:.0f} ({m['libraries']})"
                        for name, m in summary["timing"]["modules"].items()) if summary else ""
    if summary and not modules:
        modules = "none"
    shown = lambda t: f"{1e3 * statistics.median(t):.1f} ({1e3 * min(t):.1f})" if t else ""
    print(f"| {label} | {shown(now)} | {shown(before)} | {nodes} | {modules} |", flush=True)
print(f"\n{repeats} runs each, one thread (OMP_NUM_THREADS=1), {time.strftime('%Y-%m-%d')}.")
