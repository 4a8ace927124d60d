"""Plots of the organ study: each meshless way's error against the tet10
reference by node spacing, at the top, at the end and in strain energy.

usage: /usr/bin/python3 organ.py RESULTS_DIR   (reads organ.json, writes organ.png)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "organ.json")) as f:
    study = json.load(f)
points = [p for p in study["points"] if p["status"] == "ok"]
ways = list(dict.fromkeys(p["way"] for p in points))

fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
for ax, key, title in ((axes[0], "top", "Sag at the top"), (axes[1], "end", "Sag at the end"),
                       (axes[2], "energy", "Strain energy")):
    for i, w in enumerate(ways):
        line = sorted((p["spacing_m"], p[key + "_error_percent"]) for p in points if p["way"] == w)
        ax.loglog([1e3 * h for h, _ in line], [abs(e) for _, e in line], "o-", color=f"C{i}", label=w)
        below = [(h, e) for h, e in line if e < 0]
        ax.plot([1e3 * h for h, _ in below], [abs(e) for _, e in below], "o", mfc="white", color=f"C{i}")
    ax.axhline(3.0, color="grey", lw=0.8, ls=":")
    ax.set_xlabel("node spacing (mm)")
    ax.set_ylabel("|error| against tet10 (%)")
    ax.set_title(title + " (open: stiffer than the reference)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(out, "organ.png"), dpi=120)
