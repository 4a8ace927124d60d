#!/usr/bin/env bash
# A scene run under mpirun on 2 and 3 ranks (KERF_TEST_RANKS: others) gives the serial run's probes:
# to TOLERANCE relative (1e-10 with a direct solve; the solver's tolerance
# with CG), and says whether each rank assembled its own cells (PARTITIONED:
# true or false; divided: its own cells of a mesh divided among the ranks,
# each holding its piece). Its last ParaView step is a .pvtu whose pieces hold every
# serial cell once with the serial displacements (PIECES_CHECK: the program
# pieces_match_serial); with KERF_TEST_VTK=off no ParaView output, so that
# the probes are read every step from the state alone; with KERF_TEST_MAX_TOUCHED=F rank 0 computes
# values in at most F times its own rows (its cells or points fall mostly in its own rows). usage:
#   ranks_match_serial.sh KERF PIECES_CHECK OUT_DIR TOLERANCE PARTITIONED SCENE [--set KEY=VALUE]...
set -u
kerf=$1 pieces_check=$2 out=$3 tolerance=$4 partitioned=$5 scene=$6
shift 6
here=$(dirname "$0")
rm -rf "$out"
fail() { echo "FAILED: $*"; exit 1; }
# The first and last steps of a dynamic run in ParaView (a static one writes each load step).
few_vtk_steps="output.vtk.every=1000000"
[ "${KERF_TEST_VTK:-on}" = off ] && few_vtk_steps="output.vtk=false"
last_step() { python3 -c "import re,sys; print(re.findall(r'part=\"0\" file=\"([^\"]+)\"', open(sys.argv[1]).read())[-1])" "$1"/*.pvd; }
"$kerf" run "$scene" "$@" --set "$few_vtk_steps" --out "$out/serial" --quiet || fail "the serial run failed"
for ranks in ${KERF_TEST_RANKS:-2 3}; do
  mpirun --allow-run-as-root --oversubscribe -np "$ranks" "$kerf" run "$scene" "$@" --set "$few_vtk_steps" \
    --out "$out/ranks$ranks" --quiet || fail "the run on $ranks ranks failed"
  echo "$ranks ranks against serial:"
  python3 "$here/same_probes.py" "$out/serial/summary.json" "$out/ranks$ranks/summary.json" "$tolerance" || exit 1
  python3 - "$out/ranks$ranks/summary.json" "$ranks" "$partitioned" "${KERF_TEST_MAX_TOUCHED:-}" <<'CHECK' || exit 1
import json, sys
summary = json.load(open(sys.argv[1]))
parallel = summary["parallel"]
print("parallel:", parallel)
expected = {"ranks": int(sys.argv[2]), "partitioned": sys.argv[3] in ("true", "divided"),
            "mesh_divided": sys.argv[3] == "divided"}
if any(parallel[key] != value for key, value in expected.items()):
    sys.exit(f"FAILED: the summary's parallel section says {parallel}, expected {expected}")
# A body not divided among the ranks says so, naming the key; a divided one says nothing of the kind.
whole = [n for n in summary.get("notes", []) if "the body is not divided among them: " in n]
if (sys.argv[3] == "divided") == bool(whole):
    sys.exit(f"FAILED: notes {whole} for a body that is {'divided' if sys.argv[3] == 'divided' else 'whole'}")
print("whole on every rank:", whole)
if sys.argv[4]:
    touched, owned = parallel["rank0_touched_rows"], parallel["rank0_owned_rows"]
    if touched > float(sys.argv[4]) * owned:
        sys.exit(f"FAILED: rank 0 computes values in {touched} rows, more than {sys.argv[4]} x its own {owned}")
# Central differences on a partitioned body without contact step each rank's piece, exchanging only ghosts' forces.
scene = summary["scene"]
pieces = (sys.argv[3] in ("true", "divided") and scene["solve"]["integrator"] == "central-difference"
          and scene["solve"]["analysis"] == "dynamic" and not scene["contact"])
if parallel["state_in_pieces"] != pieces:
    sys.exit(f"FAILED: state_in_pieces is {parallel['state_in_pieces']}, expected {pieces}")
CHECK
  [ "${KERF_TEST_VTK:-on}" = off ] && continue
  "$pieces_check" "$out/serial/$(last_step "$out/serial")" "$out/ranks$ranks/$(last_step "$out/ranks$ranks")" \
    "$ranks" "$tolerance" || exit 1
done
echo "ok"
