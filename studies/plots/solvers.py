"""Plot of the solvers study: median FEM implicit step against node count, one line per linear solver.

usage: /usr/bin/python3 solvers.py RESULTS_DIR   (reads solvers.json, writes solvers.png)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "solvers.json")) as f:
    study = json.load(f)
points = [p for p in study["points"] if p["status"] == "ok"]
fig, ax = plt.subplots(figsize=(7, 4.5))
for solver in dict.fromkeys(p["solver"] for p in points):
    mine = sorted((p for p in points if p["solver"] == solver), key=lambda p: p["nodes"])
    ax.plot([p["nodes"] for p in mine], [p["step_median_ms"] for p in mine], "o-", label=f"{solver}: median step")
    ax.plot([p["nodes"] for p in mine], [p["step_max_ms"] for p in mine], "x:", color=ax.lines[-1].get_color(),
            label=f"{solver}: first step (largest)")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("nodes (tet4)")
ax.set_ylabel("time per step (ms)")
ax.set_title("FEM implicit Euler step, corotational, one linearised solve")
ax.legend(fontsize=7)
ax.grid(True, which="both", lw=0.3)
fig.tight_layout()
fig.savefig(os.path.join(out, "solvers.png"), dpi=120)
