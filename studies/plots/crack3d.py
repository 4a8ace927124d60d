"""Plots of the 3D crack study: each method's crack-opening error against the
converged tet10 reference by spacing (at the centre and behind the front),
and how much the opening behind the front varies through the thickness.

usage: /usr/bin/python3 crack3d.py RESULTS_DIR   (reads crack3d.json, writes crack3d.png)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "crack3d.json")) as f:
    study = json.load(f)
points = [p for p in study["points"] if p["status"] == "ok"]
methods = list(dict.fromkeys(p["method"] for p in points))
colour = {m: f"C{i}" for i, m in enumerate(methods)}


def line_of(method, key):
    return sorted((p["spacing_m"], p[key]) for p in points if p["method"] == method and key in p and p[key] != 0.0)


fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
for ax, key, title in ((axes[0], "centre", "Opening at the centre"),
                       (axes[1], "front", "Opening 1 mm behind the front")):
    for m in methods:
        line = line_of(m, key + "_error_percent")
        if not line:
            continue
        order = study["observed_order"].get(m, {}).get(key)
        label = m + (f" (order {order:.2f})" if order is not None else "")
        style = "o--" if m.endswith("_tips") else "o-"  # refined at the crack's tips
        ax.loglog([1e3 * h for h, _ in line], [abs(e) for _, e in line], style, label=label, color=colour[m])
        below = [(h, e) for h, e in line if e < 0]
        ax.plot([1e3 * h for h, _ in below], [abs(e) for _, e in below], "o", mfc="white", color=colour[m])
    ax.set_xlabel("spacing or element size (mm)")
    ax.set_ylabel("|error| against tet10, tips refined, 0.7 mm (%)")
    ax.set_title(title + " (open: below the reference)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)

ax = axes[2]
for m in methods:
    line = line_of(m, "front_through_thickness_percent")
    if line:
        ax.plot([1e3 * h for h, _ in line], [e for _, e in line], "o--" if m.endswith("_tips") else "o-", label=m,
                color=colour[m])
ax.axhline(0.0, color="grey", lw=0.8)
ax.set_xlabel("spacing or element size (mm)")
ax.set_ylabel("opening on the face against mid-plane (%)")
ax.set_title("Along the front (plane strain: 0)")
ax.grid(True, alpha=0.3)
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(out, "crack3d.png"), dpi=110)
