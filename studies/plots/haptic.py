"""Plot of the haptic study: each method's time per loop iteration, cutting every step and not (the floor).

usage: /usr/bin/python3 haptic.py RESULTS_DIR   (reads haptic.json and iterations.csv, writes haptic.png)
"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "haptic.json")) as f:
    study = json.load(f)
trace = {}
with open(os.path.join(out, "iterations.csv"), newline="") as f:
    for row in csv.DictReader(f):
        trace.setdefault((row["method"], row["loop"]), []).append(float(row["ms"]))
methods = list(dict.fromkeys(p["method"] for p in study["points"]))
fig, axes = plt.subplots(1, len(methods), figsize=(4 * len(methods), 3.8), squeeze=False)
for ax, method in zip(axes[0], methods):
    for loop, style in (("cut", "-"), ("floor", ":")):
        times = trace.get((method, loop), [])
        ax.plot(range(1, len(times) + 1), times, style, lw=0.8, label=f"{loop}" + (" (no blade)" if loop == "floor"
                                                                                 else " (blade every step)"))
    ax.axhline(1.0, color="red", lw=0.6, label="1 ms (1 kHz)")
    ax.set_yscale("log")
    ax.set_xlabel("iteration (1 ms step)")
    ax.set_title(method)
    ax.grid(True, which="both", lw=0.3)
axes[0][0].set_ylabel("read tool + cut + step + force (ms)")
axes[0][0].legend(fontsize=7)
fig.suptitle(f"haptic loop, {study.get('threads', '?')} OpenMP threads, OMP_WAIT_POLICY "
             f"{study.get('omp_wait_policy', '?')}", fontsize=9)
fig.tight_layout()
fig.savefig(os.path.join(out, "haptic.png"), dpi=120)
