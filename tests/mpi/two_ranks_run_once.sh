#!/usr/bin/env bash
# Under mpirun a serial linear solver is refused before any work: exit code 2,
# the reason printed once (by rank 0) naming solve.linear_solver, nothing
# written; with petsc the scene runs, rank 0 alone printing and writing.
# usage: two_ranks_run_once.sh KERF SCENE OUT_DIR
set -u
kerf=$1 scene=$2 out=$3
rm -rf "$out"
log=$(mpirun --allow-run-as-root --oversubscribe -np 2 "$kerf" run "$scene" --out "$out" 2>&1)
code=$?
echo "$log"
fail() { echo "FAILED: $*"; exit 1; }
[ "$code" -eq 2 ] || fail "exit code $code, expected 2"
[ "$(grep -c "key 'solve.linear_solver': cholmod cannot run on 2 MPI ranks" <<<"$log")" -eq 1 ] ||
  fail "the refusal is not printed exactly once"
[ ! -e "$out" ] || fail "$out was written"
# The same scene with PETSc's solver runs on both ranks; rank 0 alone prints
# its progress and writes the results.
log=$(mpirun --allow-run-as-root --oversubscribe -np 2 "$kerf" run "$scene" --set solve.linear_solver=petsc \
  --out "$out" 2>&1) || fail "the petsc run failed: $log"
echo "$log"
[ "$(grep -c "kerf: results in $out" <<<"$log")" -eq 1 ] || fail "the results line is not printed exactly once"
grep -q '"status": "ok"' "$out/summary.json" || fail "the petsc run's summary does not say ok"
echo "ok"
