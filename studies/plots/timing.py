"""Plot of the timing study: median step time of each configuration, phases stacked, paper's figures beside.

usage: /usr/bin/python3 timing.py RESULTS_DIR   (reads timing.json, writes timing.png)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "timing.json")) as f:
    study = json.load(f)
points = [p for p in study["points"] if p["status"] == "ok"]
labels = [f"{p['problem']}: {p['configuration']} ({p['nodes']} nodes)" for p in points]
fig, ax = plt.subplots(figsize=(10, 0.45 * len(points) + 1.5))
y = range(len(points))
ax.barh(y, [p["step_median_ms"] for p in points], color="lightgrey", label="median step")
left = [0.0] * len(points)
for phase, colour in (("assembly_ms", "tab:blue"), ("factorize_ms", "tab:orange"), ("solve_ms", "tab:green")):
    widths = [p[phase] for p in points]
    ax.barh(y, widths, left=left, height=0.4, color=colour, label=phase.replace("_ms", " (mean per step)"))
    left = [a + b for a, b in zip(left, widths)]
paper = study["paper"]
for value, text, style in ((paper["fem_ms_per_step"], "paper FEM 195 ms", "--"),
                           (paper["meshless_ms_per_step"], "paper meshless 20.11 ms", ":"),
                           (1e3 / paper["block_fps"], "paper block 125 FPS", "-.")):
    ax.axvline(value, color="black", ls=style, lw=1, label=text)
ax.set_xscale("log")
ax.set_yticks(list(y))
ax.set_yticklabels(labels, fontsize=8)
ax.invert_yaxis()
ax.set_xlabel("time per step (ms)")
ax.set_title("Per-step time, phase by phase")
ax.legend(fontsize=7, loc="lower right")
ax.grid(True, axis="x", which="both", lw=0.3)
fig.tight_layout()
fig.savefig(os.path.join(out, "timing.png"), dpi=120)
