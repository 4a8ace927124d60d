"""Plot of the pareto study: wall time against error, per problem, each method a line through its resolutions.

usage: /usr/bin/python3 pareto.py RESULTS_DIR   (reads pareto.json, writes pareto.png)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "pareto.json")) as f:
    study = json.load(f)
points = [p for p in study["points"] if p["status"] == "ok"]
methods = sorted({p["method"] for p in points})
colours = dict(zip(methods, plt.rcParams["axes.prop_cycle"].by_key()["color"]))
titles = {"hertz": "Hertz indentation (graded block, a/R = 0.1)",
          "crack": "Crack opening (2 cm crack, plane strain)"}

fig, axes = plt.subplots(1, 2, figsize=(12, 5))
for ax, problem in zip(axes, ("hertz", "crack")):
    for method in methods:
        series = sorted((p for p in points if p["problem"] == problem and p["method"] == method),
                        key=lambda p: p["wall_s"])
        if not series:
            continue
        ax.loglog([p["wall_s"] for p in series], [max(p["error_percent"], 1e-3) for p in series], "o-",
                  color=colours[method], label=method)
        for p in series:
            label = f"a/{p['resolution']:g}" if problem == "hertz" else f"{1e3 * p['resolution']:g} mm"
            ax.annotate(label, (p["wall_s"], max(p["error_percent"], 1e-3)), fontsize=6,
                        textcoords="offset points", xytext=(3, 3))
    front = study["fronts"][problem]
    if front:
        xs, ys = [], []
        for p in front:  # a staircase: the best error reachable within a time budget
            if xs:
                xs.append(p["wall_s"])
                ys.append(ys[-1])
            xs.append(p["wall_s"])
            ys.append(max(p["error_percent"], 1e-3))
        ax.plot(xs, ys, color="grey", lw=3, alpha=0.35, label="Pareto front")
    ax.set_xlabel("wall time of the run (s): setup + solve")
    ax.set_ylabel("|error| (%)")
    ax.set_title(titles[problem])
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(out, "pareto.png"), dpi=110)
