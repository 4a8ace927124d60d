"""Plots of the Hertz study: |error| against Hertz and against the converged
reference, and the indentation, against node count.

usage: /usr/bin/python3 hertz.py RESULTS_DIR   (reads hertz.json, writes hertz.png)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(os.path.join(out, "hertz.json")) as f:
    study = json.load(f)
points = [p for p in study["points"] if p["status"] == "ok"]
methods = sorted({p["method"] for p in points})
colours = dict(zip(methods, plt.rcParams["axes.prop_cycle"].by_key()["color"]))
hertz = study["hertz"]["indentation_m"]

fig, (ax_error, ax_reference, ax_depth) = plt.subplots(1, 3, figsize=(16, 4.5))
reference = study["reference"]["indentation_m"]
rates = study["rates_against_reference"]
for method in methods:
    for family, style in (("graded", "o-"), ("uniform", "s--")):
        series = sorted((p for p in points if p["method"] == method and p["family"] == family),
                        key=lambda p: p["nodes"])
        if not series:
            continue
        nodes = [p["nodes"] for p in series]
        label = f"{method} ({family})"
        ax_error.loglog(nodes, [abs(p["error_percent"]) for p in series], style, color=colours[method], label=label)
        if family == "graded":
            order = rates[method]["order"]
            ax_reference.loglog(nodes, [abs(p["error_vs_reference_percent"]) for p in series], style,
                                color=colours[method],
                                label=method + (f" (order {order:.2f})" if order is not None else ""))
        ax_depth.semilogx(nodes, [1e3 * p["indentation_m"] for p in series], style, color=colours[method],
                          label=label)
ax_error.axhline(study["bound_percent"], color="grey", lw=0.8, ls=":")
ax_error.set_xlabel("nodes")
ax_error.set_ylabel("|indentation error| against Hertz (%)")
ax_error.set_title("Convergence to Hertz (a/R = 0.1)")
ax_error.grid(True, which="both", lw=0.3)
ax_reference.axhline(study["fit_floor_percent"], color="grey", lw=0.8, ls=":")
ax_reference.set_xlabel("nodes")
ax_reference.set_ylabel("|indentation error| against the reference (%)")
ax_reference.set_title(f"Against {study['reference']['method']} converged (orders in h)")
ax_reference.grid(True, which="both", lw=0.3)
ax_reference.legend(fontsize=7)
ax_depth.axhline(1e3 * hertz, color="black", lw=1.0, label="Hertz")
ax_depth.axhline(1e3 * reference, color="black", lw=0.8, ls="--", label="reference")
ax_depth.set_xlabel("nodes")
ax_depth.set_ylabel("indentation (mm)")
ax_depth.set_title("Indentation under the Hertz force (cf. paper Fig. 2)")
ax_depth.grid(True, which="both", lw=0.3)
ax_depth.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(out, "hertz.png"), dpi=120)
