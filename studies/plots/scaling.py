"""Plots of the scaling study: speed-up per phase against ranks (strong
scaling, one panel per problem) and time per phase against ranks (weak);
below, the largest rank's peak memory against ranks (1/N from one rank's).

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
fig, axes = plt.subplots(2, max(1, len(problems)), figsize=(4.5 * max(1, len(problems)), 8), squeeze=False)
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
for ax, problem in zip(axes[1], problems):
    mine = sorted((p for p in points if p["problem"] == problem and p["threads"] == 1), key=lambda p: p["ranks"])
    ranks = [p["ranks"] for p in mine]
    for key, label in (("largest_rank_peak_memory_mb", "peak"), ("largest_rank_memory_after_body_mb", "after body")):
        if all(key in p for p in mine):
            ax.plot(ranks, [p[key] for p in mine], "o-", label=label)
    if "largest_rank_peak_memory_mb" in mine[0] and not problem.startswith("weak"):
        ax.plot(ranks, [mine[0]["largest_rank_peak_memory_mb"] / r for r in ranks], ":", color="grey", label="1/N")
    ax.set_ylabel("largest rank's memory (MB)")
    ax.set_xlabel("MPI ranks")
    ax.set_xticks(ranks)
    ax.set_ylim(bottom=0)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(out, "scaling.png"), dpi=120)
