"""Plots of the cut convergence study: each method's sag and opening error
against the converged tet10 reference by spacing, and direct nodal
integration's answer as the cut moves off the lattice.

usage: /usr/bin/python3 cut_convergence.py RESULTS_DIR   (reads cut_convergence.json, writes cut_convergence.png)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "cut_convergence.json")) as f:
    study = json.load(f)
points = [p for p in study["points"] if p["status"] == "ok"]
methods = list(dict.fromkeys(p["method"] for p in points))
colour = {m: f"C{i}" for i, m in enumerate(methods)}  # the same method, the same colour in every panel

fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
for ax, key, title in ((axes[0], "sag_error_percent", "End sag"), (axes[1], "opening_error_percent", "Opening")):
    for m in methods:
        line = sorted((p["spacing_m"], p[key]) for p in points if p["method"] == m and key in p)
        line = [(h, e) for h, e in line if e != 0.0]
        if not line:
            continue
        order = study["observed_order"].get(m, {}).get(key.split("_")[0])
        label = m + (f" (order {order:.2f})" if order is not None else "")
        drawn = ax.loglog([1e3 * h for h, _ in line], [abs(e) for _, e in line], "o-", label=label, color=colour[m])
        below = [(h, e) for h, e in line if e < 0]
        ax.plot([1e3 * h for h, _ in below], [abs(e) for _, e in below], "o", mfc="white",
                color=drawn[0].get_color())
    ax.set_xlabel("spacing or element size (mm)")
    ax.set_ylabel("|error| against tet10 remesh at 1 mm (%)")
    ax.set_title(title + " (open: below the reference)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)

ax = axes[2]
h = study["sweep_spacing_m"]
for m in methods:
    if m == "fem_tet10_remesh":
        continue
    swept = [p for p in points if p["method"] == m and p["spacing_m"] == h and "sweep_sag_error_percent" in p]
    both = sorted((p["shift_plane_m"], p["sweep_sag_error_percent"]) for p in swept
                  if p["shift_plane_m"] == p["shift_front_m"])
    if not both:
        continue
    drawn = ax.plot([1e3 * s for s, _ in both], [e for _, e in both], "o-", label=m + ": plane and front moved",
                    color=colour[m])
    for p in swept:
        if p["shift_plane_m"] != p["shift_front_m"]:
            alone = "plane" if p["shift_plane_m"] > 0 else "front"
            ax.plot(1e3 * max(p["shift_plane_m"], p["shift_front_m"]), p["sweep_sag_error_percent"],
                    "s" if alone == "plane" else "^", color=drawn[0].get_color(), mfc="none",
                    label=m + ": " + alone + " alone")
ax.set_xscale("symlog", linthresh=0.01)
ax.axhline(0.0, color="grey", lw=0.8)
ax.set_xlabel("cut moved off the lattice's nodes (mm)")
ax.set_ylabel("sag error against tet10 on the same cut (%)")
ax.set_title(f"Nodes on the cut at {1e3 * h:g} mm spacing")
ax.grid(True, alpha=0.3)
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(out, "cut_convergence.png"), dpi=110)
