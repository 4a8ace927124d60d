"""The tip deflections of the example's three runs: the law with c2 = 0 equals
kerf's neo-Hookean to round-off (relative 1e-9: measured 2e-16), and with
c2 = 1e5 Pa it differs from it by more than 1e-4 (measured 6e-4: the moduli
at rest are the same, and the beam bends at small strain)."""
import json
import sys


def tip_z(run):
    with open(f"{sys.argv[1]}/{run}/summary.json") as f:
        summary = json.load(f)
    if summary["status"] != "ok":
        sys.exit(f"{run}: status {summary['status']}: {summary.get('error')}")
    return summary["probes"]["tip"]["displacement"][2]


zero, builtin, positive = tip_z("c2_zero"), tip_z("neohookean"), tip_z("c2_positive")
print(f"tip z: c2 = 0 {zero!r} m, kerf's neo-Hookean {builtin!r} m, c2 = 1e5 Pa {positive!r} m")
if abs(zero - builtin) > 1e-9 * abs(builtin):
    sys.exit(f"c2 = 0 differs from neo-Hookean by {abs(zero - builtin) / abs(builtin):.3g} (relative)")
if abs(positive - builtin) < 1e-4 * abs(builtin):
    sys.exit("c2 > 0 gives the neo-Hookean deflection: the parameter is not used")
