"""Plots of the scaling study: speed-up per phase against ranks (strong
scaling, one panel per problem) and time per phase against ranks (weak).

usage: /usr/bin/python3 scaling.py RESULTS_DIR   (reads scaling.json, writes scaling.png)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "scaling.json")) as f:
    study = json.load(f)
points = [p for p in study["points"] if p["status"] == "ok"]
problems = list(dict.fromkeys(p["problem"] for p in points))
phases = ["setup", "assembly", "factorize", "solve"]
fig, axes = plt.subplots(1, max(1, len(problems)), figsize=(4.5 * max(1, len(problems)), 4), squeeze=False)
for ax, problem in zip(axes[0], problems):
    mine = sorted((p for p in points if p["problem"] == problem and p["threads"] == 1), key=lambda p: p["ranks"])
    ranks = [p["ranks"] for p in mine]
    if problem.startswith("weak"):
        for phase in phases:
            ax.plot(ranks, [p[phase + "_s"] for p in mine], "o-", label=phase)
        ax.plot(ranks, [p["wall_s"] for p in mine], "k^--", label="wall")
        ax.set_ylabel("time (s), dofs per rank held")
        ax.set_title(f"{problem}: {mine[0]['dofs']}-{mine[-1]['dofs']} dofs")
    else:
        one = mine[0]
        for phase in phases + ["loop"]:
            if one[phase + "_s"] > 0:
                ax.plot(ranks, [one[phase + "_s"] / p[phase + "_s"] for p in mine], "o-", label=phase)
        ax.plot(ranks, [one["wall_s"] / p["wall_s"] for p in mine], "k^--", label="wall")
        ax.plot(ranks, ranks, ":", color="grey", label="ideal")
        ax.set_ylabel("speed-up against 1 rank")
        ax.set_title(f"{problem}: {one['dofs']} dofs")
    ax.set_xlabel(f"MPI ranks (1 thread each; {study['cores']} cores, 3 oversubscribed)")
    ax.set_xticks(ranks)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(out, "scaling.png"), dpi=120)
