#!/usr/bin/env bash
# An error under mpirun stops every rank, never a hang: rank 0 alone failing
# (it alone creates the output folder) and every rank failing alike (a linear
# solve that diverges), each printed once, the exit code 1, and in the second
# case summary.json readable with status "error".
# usage: errors_stop_every_rank.sh KERF SCENE OUT_DIR
set -u
kerf=$1 scene=$2 out=$3
rm -rf "$out"
fail() { echo "FAILED: $*"; exit 1; }
launch() { timeout 60 mpirun --allow-run-as-root --oversubscribe -np 3 "$kerf" run "$scene" \
  --set solve.linear_solver=petsc "$@" 2>&1; }

log=$(launch --out /dev/null/cannot_be_made)
code=$?
echo "$log"
[ "$code" -ne 124 ] || fail "rank 0 alone failing left the other ranks waiting (killed after 60 s)"
[ "$code" -eq 1 ] || fail "exit code $code, expected 1"
[ "$(grep -c "kerf: error: .*cannot create directories" <<<"$log")" -eq 1 ] || fail "the error is not printed once"

log=$(launch --set "solve.petsc=-ksp_type cg -pc_type none -ksp_max_it 2" --out "$out")
code=$?
echo "$log"
[ "$code" -ne 124 ] || fail "a failure on every rank hung (killed after 60 s)"
[ "$code" -eq 1 ] || fail "exit code $code, expected 1"
[ "$(grep -c "kerf: error: .*KSP diverged" <<<"$log")" -eq 1 ] || fail "the error is not printed once"
grep -q '"status": "error"' "$out/summary.json" || fail "summary.json does not say error"
echo "ok"
