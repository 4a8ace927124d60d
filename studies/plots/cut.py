"""Plots of the cut study: the end's sag and the opening over time, and the update times.

usage: /usr/bin/python3 cut.py RESULTS_DIR   (reads cut.json and the runs' probes.csv, writes cut.png)
"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "cut.json")) as f:
    study = json.load(f)

fig, (ax_sag, ax_open, ax_update) = plt.subplots(1, 3, figsize=(15, 4.5))
for way, run in study["runs"].items():
    path = os.path.join(out, "runs", way, "probes.csv")
    if not os.path.exists(path):
        continue
    with open(path) as f:
        rows = list(csv.DictReader(f))
    t = [float(r["time"]) for r in rows]
    ax_sag.plot(t, [-1e3 * float(r["end_uz"]) for r in rows], label=way)
    ax_open.plot(t, [1e3 * (float(r["behind_ux"]) - float(r["before_ux"])) for r in rows], label=way)
ax_sag.set_xlabel("time (s)")
ax_sag.set_ylabel("sag of the free end (mm)")
ax_sag.set_title("Block sagging while it is cut")
ax_sag.legend(fontsize=7)
ax_open.set_xlabel("time (s)")
ax_open.set_ylabel("opening 4 mm either side of the blade (mm)")
ax_open.set_title("The cut opening under the sag")

ways = [w for w, r in study["runs"].items() if r["status"] == "ok" and r.get("updates")]
x = range(len(ways))
ax_update.bar([i - 0.2 for i in x], [study["runs"][w]["update_ms_median"] for w in ways], 0.4, label="median")
ax_update.bar([i + 0.2 for i in x], [study["runs"][w]["update_ms_max"] for w in ways], 0.4, label="max")
ax_update.set_yscale("log")
ax_update.set_xticks(list(x))
ax_update.set_xticklabels(ways)
ax_update.set_ylabel("time of one cut update (ms)")
ax_update.set_title("Following the cut: one update per blade move")
ax_update.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(out, "cut.png"), dpi=110)
