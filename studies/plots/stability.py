"""Plots of the stability study: critical steps, undamped energy, the zigzag cut, locking.

usage: /usr/bin/python3 stability.py RESULTS_DIR   (reads stability.json and the runs, writes stability.png)
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "stability.json")) as f:
    study = json.load(f)


def number(value):
    return value if isinstance(value, (int, float)) else math.nan


def paired_bars(ax, cases, left, right, left_label, right_label, rotation=0):
    """Two bars per case (left and right values), the cases named under them."""
    x = range(len(cases))
    ax.bar([i - 0.2 for i in x], [number(v) for v in left], 0.4, label=left_label)
    ax.bar([i + 0.2 for i in x], [number(v) for v in right], 0.4, label=right_label)
    ax.set_xticks(list(x))
    ax.set_xticklabels(cases, rotation=rotation, fontsize=8)


fig, axes = plt.subplots(2, 2, figsize=(12, 8.5))

# Critical steps: largest stable and first unstable dt over the Lanczos estimate.
ax = axes[0][0]
critical = study["critical_step"]
methods = list(critical)
paired_bars(ax, methods, [critical[m]["largest_stable_factor"] for m in methods],
            [critical[m]["first_unstable_factor"] for m in methods], "largest stable dt", "first unstable dt", 20)
bounds = [number(critical[m]["element_bound_s"]) / critical[m]["estimate_s"] for m in methods]
ax.plot(range(len(methods)), bounds, "k_", markersize=18, label="FEM element bound")
ax.axhline(1.0, color="grey", lw=0.8, ls=":")
ax.set_ylabel("dt / critical-step estimate (Lanczos)")
ax.set_title("Central differences: where stability ends")
ax.legend(fontsize=7)

# Undamped energy: (K + U - W) / max U over time, per method.
ax = axes[0][1]
for m in study["energy_drift"]:
    path = os.path.join(out, "runs", "drift_" + m, "probes.csv")
    if not os.path.exists(path):
        continue
    with open(path) as f:
        rows = list(csv.DictReader(f))
    t = [float(r["time"]) for r in rows]
    k = [float(r["energy_kinetic"]) for r in rows]
    u = [float(r["energy_strain"]) for r in rows]
    w = [float(r["energy_external_work"]) for r in rows]
    peak = max((v for v in u if math.isfinite(v)), default=0.0) or 1.0
    ax.plot(t, [(a + b - c) / peak for a, b, c in zip(k, u, w)], lw=0.7, label=m)
ax.set_xlabel("time (s)")
ax.set_ylabel("(kinetic + strain - work) / max strain")
ax.set_title("Undamped corotational cantilever at 0.9 of the estimate")
ax.legend(fontsize=7)

# The zigzag: condition numbers and the growing run's energy.
ax = axes[1][0]
zigzag = study["zigzag"]
rules = list(zigzag)
paired_bars(ax, rules, [zigzag[r]["condition_near_cut_max"] for r in rules],
            [zigzag[r]["growing_mechanical_over_work"] for r in rules], "max condition, enriched nodes",
            "growing cut: max (K + U) / max work")
ax.set_yscale("log")
ax.set_title("200-piece zigzag cut (nodal, 2D)")
ax.legend(fontsize=7)

# Locking.
ax = axes[1][1]
locking = study["locking"]
methods = [m for m in locking if isinstance(locking[m], dict)]
paired_bars(ax, methods, [locking[m]["deflection_over_reference_nu0.3"] for m in methods],
            [locking[m]["deflection_over_reference_nu0.49"] for m in methods], "nu = 0.3", "nu = 0.49", 20)
ax.axhline(1.0, color="grey", lw=0.8, ls=":")
ax.set_ylabel("tip deflection / tet10 reference")
ax.set_title("Near-incompressible locking (end-loaded cantilever)")
ax.legend(fontsize=7)

fig.tight_layout()
fig.savefig(os.path.join(out, "stability.png"), dpi=110)
