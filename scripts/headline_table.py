"""Writes DIR/README.md: the headline figures of every study found in DIR/<study>/<study>.json.

usage: /usr/bin/python3 scripts/headline_table.py DIR
"""
import glob
import json
import os
import sys


def rounded(value):
    """Three significant digits for a number; anything else as it is."""
    return f"{value:.3g}" if isinstance(value, (int, float)) and not isinstance(value, bool) else str(value)


out = sys.argv[1]
lines = ["# Results of the main job", "",
         "Written by `make run` (scripts/main_job.sh); each study ran in its quick mode",
         "(`kerf study NAME --quick`). The committed full runs are in results/ of the repository.", ""]
for path in sorted(glob.glob(os.path.join(out, "*", "*.json"))):
    name = os.path.basename(os.path.dirname(path))
    if os.path.basename(path) != name + ".json":
        continue
    with open(path) as f:
        study = json.load(f)
    lines += [f"## {name}" + (" (quick)" if study.get("quick") else ""), ""]
    rows = [h for h in study.get("headline", []) if h.get("value") is not None]
    if rows:  # a study whose quick mode has no headline figure gets no empty table
        lines += ["| figure | value |", "|---|---|"]
        lines += [f"| {h['what']} | {rounded(h['value'])} {h.get('unit', '')} |" for h in rows]
    else:
        lines.append(f"No headline figure in this mode: see `{name}/` (its CSV and JSON).")
    lines.append("")
    for plot in study.get("plots", []):
        lines.append(f"![{name}]({name}/{plot})")
    lines.append("")
pictures = sorted(glob.glob(os.path.join(out, "pictures", "*.png")))
if pictures:
    lines += ["## The cut block at its last step, in ParaView", "",
              "Rendered by ParaView itself (pvbatch, scripts/paraview_pictures.py) from the cut study's",
              "series: the body warped by its displacement and coloured by von Mises stress (Pa), the cut",
              "surface in black at its reference place.", ""]
    lines += [f"![{os.path.basename(p)[:-4]}]({os.path.relpath(p, out)}) " for p in pictures]
    lines.append("")
scenes = sorted(glob.glob(os.path.join(out, "scenes", "*", "*.pvd")))
if scenes:
    lines += ["## ParaView series of the example scenes", ""]
    lines += [f"- `{os.path.relpath(p, out)}`" for p in scenes]
    lines.append("")
with open(os.path.join(out, "README.md"), "w") as f:
    f.write("\n".join(lines))
print(os.path.join(out, "README.md"))
