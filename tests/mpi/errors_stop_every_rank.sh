#!/usr/bin/env bash
# An error under mpirun stops every rank, never a hang, printed once with the
# exit code the serial run gives: a bad scene (2); rank 0 alone failing (it
# alone creates the output folder; it alone reads a mesh file, here not one,
# while the others wait for the mesh); every rank failing alike (a linear solve
# that diverges; a singular stiffness: the body held in x only); and rank 1
# alone failing (its ParaView piece cannot be written), whose summary.json
# rank 1 then writes itself, naming the rank.
# usage: errors_stop_every_rank.sh KERF SCENE OUT_DIR
set -u
kerf=$1 scene=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
fail() { echo "FAILED: $*"; exit 1; }
launch() { timeout 60 mpirun --allow-run-as-root --oversubscribe -np 3 "$kerf" run "$scene" \
  --set solve.linear_solver=petsc "$@" 2>&1; }
# expect_stop EXPECTED_CODE MESSAGE_PATTERN LOG CODE
expect_stop() {
  echo "$3"
  [ "$4" -ne 124 ] || fail "a rank was left waiting (killed after 60 s)"
  [ "$4" -eq "$1" ] || fail "exit code $4, expected $1"
  [ "$(grep -c "kerf: error: $2" <<<"$3")" -eq 1 ] || fail "the error '$2' is not printed once"
}
# expect_summary DIR RANK: summary.json says error, written by RANK
expect_summary() {
  python3 - "$1/summary.json" "$2" <<'CHECK' || exit 1
import json, sys
summary = json.load(open(sys.argv[1]))
if summary["status"] != "error" or summary.get("error_rank") != int(sys.argv[2]):
    sys.exit(f"FAILED: summary.json says {summary['status']} on rank {summary.get('error_rank')}, expected error on {sys.argv[2]}")
CHECK
}

log=$(launch --set material.poisson=0.7 --out "$out/bad_scene"); code=$?
expect_stop 2 ".*material.poisson" "$log" "$code"

log=$(launch --out /dev/null/cannot_be_made); code=$?
expect_stop 1 ".*cannot create directories" "$log" "$code"

echo "garbage" > "$out/not_a_mesh.msh"
log=$(launch --set "domain={mesh: $out/not_a_mesh.msh}" --out "$out/bad_mesh"); code=$?
expect_stop 1 ".*not_a_mesh.msh:1: not a gmsh mesh" "$log" "$code"
expect_summary "$out/bad_mesh" 0

log=$(launch --set "solve.petsc=-ksp_type cg -pc_type none -ksp_max_it 2" --out "$out/diverged"); code=$?
expect_stop 1 ".*KSP diverged" "$log" "$code"
expect_summary "$out/diverged" 0

log=$(launch --set "boundary.0.fix=[x]" --out "$out/singular"); code=$?
expect_stop 1 ".*static load step 1" "$log" "$code"
expect_summary "$out/singular" 0

mkdir -p "$out/rank1_alone/cantilever_0000_1.vtu"  # rank 1's first piece cannot take that name
log=$(launch --out "$out/rank1_alone"); code=$?
expect_stop 1 "rank 1: cannot move .*cantilever_0000_1.vtu" "$log" "$code"
expect_summary "$out/rank1_alone" 1
echo "ok"
