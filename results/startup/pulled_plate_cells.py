#!/usr/bin/python3
"""The 2D nodal plate pulled on an edge (scenes/plate_tension_2d.yaml at 2.2 mm, 1,104 nodes): its
boundary cells the lattice's own (background_cells: auto) against gmsh's (mesh), and /bin/true,
21 rounds interleaved, one thread. usage (source tree, idle machine): results/startup/pulled_plate_cells.py"""
import json, os, statistics, subprocess, sys, tempfile, time
kerf = "build/cli/kerf"
plate = "scenes/plate_tension_2d.yaml"
base = [kerf, "run", plate, "--quiet", "--set", "discretization.method=nodal", "--set",
        "discretization.meshless.spacing=0.0022", "--set", "output.vtk=false"]
cases = {"lattice": base, "mesh": base + ["--set", "discretization.meshless.background_cells=mesh"],
         "floor": ["/bin/true"]}
env = dict(os.environ, OMP_NUM_THREADS="1")
times = {k: [] for k in cases}
summaries = {}
with tempfile.TemporaryDirectory() as out:
    for _ in range(21):
        for k, c in cases.items():
            s = time.perf_counter()
            subprocess.run(c + (["--out", f"{out}/{k}"] if k != "floor" else []), env=env, check=True,
                           stdout=subprocess.DEVNULL)
            times[k].append(time.perf_counter() - s)
    for k in ("lattice", "mesh"):
        summaries[k] = json.load(open(f"{out}/{k}/summary.json"))
for k, t in times.items():
    extra = ""
    if k in summaries:
        d = summaries[k]
        extra = f" nodes {d['counts']['nodes']} modules {json.dumps(d['timing']['modules'])} probes {json.dumps(d['probes'])[:200]}"
    print(f"{k:8s} median {1e3*statistics.median(t):.1f} ms (min {1e3*min(t):.1f}){extra}")
