#!/usr/bin/env python3
"""Whether two runs' summary.json give the same probes: every value of a
probe within `tolerance` relative to the largest magnitude of that probe's
values in the reference run; the same critical explicit step (the
Lanczos and the element bound, and the smallest after a cut grew) when the
reference has one; and the same
number of Newton iterations (a tangent summed wrongly across ranks still
converges to the answer, but in more iterations); and each run's memory
marks: one per rank, positive and growing from mark to mark.
usage: same_probes.py REFERENCE OTHER TOLERANCE"""
import json
import sys


def leaves(value):
    if isinstance(value, dict):
        for v in value.values():
            yield from leaves(v)
    elif isinstance(value, list):
        for v in value:
            yield from leaves(v)
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        yield float(value)


def check_memory_marks(parallel, path):
    marks = parallel.get("peak_memory_mb_by_rank")
    if marks is None:
        sys.exit(f"{path}: no peak_memory_mb_by_rank")
    phases = ("after_body", "after_initialization", "at_end")
    for phase in phases:
        if len(marks[phase]) != parallel["ranks"] or not all(m > 0 for m in marks[phase]):
            sys.exit(f"{path}: {phase} memory {marks[phase]}: expected one positive figure a rank")
    for rank in range(parallel["ranks"]):
        figures = [marks[phase][rank] for phase in phases]
        if figures != sorted(figures):
            sys.exit(f"{path}: rank {rank}'s peak memory falls from mark to mark: {figures}")
    if marks["at_end"][0] > parallel["rank0_peak_memory_mb"]:
        sys.exit(f"{path}: rank 0's last mark {marks['at_end'][0]} above its peak {parallel['rank0_peak_memory_mb']}")


def main():
    reference_path, other_path, tolerance = sys.argv[1], sys.argv[2], float(sys.argv[3])
    reference = json.load(open(reference_path))
    other = json.load(open(other_path))
    for run, path in ((reference, reference_path), (other, other_path)):
        if run.get("status") != "ok":
            sys.exit(f"{path}: status {run.get('status')}: {run.get('error', '')}")
    for run, path in ((reference, reference_path), (other, other_path)):
        check_memory_marks(run["parallel"], path)
    if reference["counts"] != other["counts"]:
        sys.exit(f"counts differ: {reference['counts']} against {other['counts']}")
    worst = 0.0
    for name, probe in reference["probes"].items():
        if name not in other["probes"]:
            sys.exit(f"{other_path}: probe '{name}' missing")
        a, b = list(leaves(probe)), list(leaves(other["probes"][name]))
        if len(a) != len(b):
            sys.exit(f"probe '{name}': {len(a)} values against {len(b)}")
        scale = max(abs(x) for x in a) or 1.0
        difference = max(abs(x - y) for x, y in zip(a, b)) / scale
        print(f"{name}: relative difference {difference:.3g}")
        worst = max(worst, difference)
    # The critical step after a cut grew too (critical_dt_min_s: measured equal to 6e-15).
    for key in ("critical_dt_s", "critical_dt_element_bound_s", "critical_dt_min_s"):
        if reference["solver"].get(key):
            a, b = reference["solver"][key], other["solver"].get(key, float("nan"))
            difference = abs(a - b) / abs(a)
            print(f"{key}: relative difference {difference:.3g}")
            worst = max(worst, difference)
    newton = (reference["solver"]["newton_iterations"], other["solver"]["newton_iterations"])
    print(f"newton iterations: {newton[0]} and {newton[1]}")
    if newton[0] != newton[1]:
        sys.exit(f"FAILED: {newton[1]} Newton iterations against the reference's {newton[0]}")
    if not worst <= tolerance:
        sys.exit(f"FAILED: relative difference {worst:.3g} above {tolerance:g}")
    print(f"ok: largest relative difference {worst:.3g} <= {tolerance:g}")


main()
