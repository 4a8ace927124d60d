"""Plots of the scaling study: speed-up per phase against ranks (strong
scaling, one panel per problem), time per phase against ranks (weak), and
the largest rank's peak memory over one rank's against ranks, every strong
problem beside the 1/N line (ranks past the cores oversubscribe them: their
memory counts, not their time).

usage: /usr/bin/python3 scaling.py RESULTS_DIR   (reads scaling.json, writes scaling.png)
"""
import json
import math
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
cores = study["cores"]


def one_thread_series(problem):
    return sorted((p for p in points if p["problem"] == problem and p["threads"] == 1), key=lambda p: p["ranks"])


def speedup_panel(ax, problem):
    mine = one_thread_series(problem)
    ranks = [p["ranks"] for p in mine]
    if problem.startswith("weak"):
        for phase in phases:
            ax.plot(ranks, [p[phase + "_s"] for p in mine], "o-", label=phase)
        ax.plot(ranks, [p["wall_s"] for p in mine], "k^--", label="wall")
        ax.set_ylabel("time (s), dofs per rank held")
        ax.set_title(f"{problem}: {mine[0]['dofs']}-{mine[-1]['dofs']} dofs", fontsize=9)
    else:
        one = mine[0]
        for phase in phases + ["loop"]:
            if one[phase + "_s"] > 0:
                ax.plot(ranks, [one[phase + "_s"] / p[phase + "_s"] for p in mine], "o-", label=phase)
        ax.plot(ranks, [one["wall_s"] / p["wall_s"] for p in mine], "k^--", label="wall")
        ax.plot(ranks, ranks, ":", color="grey", label="ideal")
        ax.set_ylabel("speed-up against 1 rank")
        ax.set_title(f"{problem}: {one['dofs']} dofs", fontsize=9)
    ax.axvspan(cores + 0.5, max(ranks) + 0.5, color="0.92", lw=0)
    ax.set_xlabel(f"MPI ranks of 1 thread (shaded: over the {cores} cores)")
    ax.set_xticks(ranks)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)


def memory_panel(ax):
    most, highest = 1, 1.05
    for problem in problems:
        mine = one_thread_series(problem)
        if problem.startswith("weak") or not all("largest_rank_peak_memory_mb" in p for p in mine):
            continue
        ranks = [p["ranks"] for p in mine]
        most = max(most, max(ranks))
        one = mine[0]["largest_rank_peak_memory_mb"]
        ratios = [p["largest_rank_peak_memory_mb"] / one for p in mine]
        highest = max(highest, max(ratios) + 0.05)
        ax.plot(ranks, ratios, "o-", label=problem)
    ranks = range(1, most + 1)
    ax.plot(ranks, [1.0 / r for r in ranks], "k:", label="1/N")
    ax.set_ylabel("largest rank's peak memory / one rank's")
    ax.set_xlabel("MPI ranks")
    ax.set_title("memory a rank (GAMG set-up included)", fontsize=9)
    ax.set_xticks(list(ranks))
    ax.set_ylim(0, highest)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)


panels = len(problems) + 1
columns = min(4, panels)
rows = math.ceil(panels / columns)
fig, axes = plt.subplots(rows, columns, figsize=(4.5 * columns, 3.8 * rows), squeeze=False)
flat = [ax for row in axes for ax in row]
for ax, problem in zip(flat, problems):
    speedup_panel(ax, problem)
memory_panel(flat[len(problems)])
for ax in flat[panels:]:
    ax.axis("off")
fig.tight_layout()
fig.savefig(os.path.join(out, "scaling.png"), dpi=110)
