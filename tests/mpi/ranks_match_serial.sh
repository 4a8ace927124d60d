#!/usr/bin/env bash
# A scene run under mpirun on 2 and 3 ranks gives the serial run's probes:
# to TOLERANCE relative (1e-8 with a direct solve; the solver's tolerance
# with CG), and says whether each rank assembled its own cells (PARTITIONED:
# true or false). usage:
#   ranks_match_serial.sh KERF OUT_DIR TOLERANCE PARTITIONED SCENE [--set KEY=VALUE]...
set -u
kerf=$1 out=$2 tolerance=$3 partitioned=$4 scene=$5
shift 5
here=$(dirname "$0")
rm -rf "$out"
fail() { echo "FAILED: $*"; exit 1; }
"$kerf" run "$scene" "$@" --set output.vtk=false --out "$out/serial" --quiet || fail "the serial run failed"
for ranks in 2 3; do
  mpirun --allow-run-as-root --oversubscribe -np "$ranks" "$kerf" run "$scene" "$@" --set output.vtk=false \
    --out "$out/ranks$ranks" --quiet || fail "the run on $ranks ranks failed"
  echo "$ranks ranks against serial:"
  python3 "$here/same_probes.py" "$out/serial/summary.json" "$out/ranks$ranks/summary.json" "$tolerance" || exit 1
  python3 - "$out/ranks$ranks/summary.json" "$ranks" "$partitioned" <<'CHECK' || exit 1
import json, sys
parallel = json.load(open(sys.argv[1]))["parallel"]
print("parallel:", parallel)
expected = {"ranks": int(sys.argv[2]), "partitioned": sys.argv[3] == "true"}
if any(parallel[key] != value for key, value in expected.items()):
    sys.exit(f"FAILED: the summary's parallel section says {parallel}, expected {expected}")
CHECK
done
echo "ok"
