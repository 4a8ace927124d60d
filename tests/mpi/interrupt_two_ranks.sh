#!/usr/bin/env bash
# SIGTERM to mpirun in the middle of a two-rank run (Open MPI passes it to
# every rank): the run stops within seconds, rank 0's summary.json says
# "interrupted (SIGTERM)", no rank is left running, and every piece the last
# .pvtu lists is whole.
# usage: interrupt_two_ranks.sh KERF SCENE OUT_DIR
set -u
kerf=$1 scene=$2 out=$3
rm -rf "$out" && mkdir -p "$(dirname "$out")"
fail() { echo "FAILED: $*"; cat "$out.log" 2>/dev/null; exit 1; }
mpirun --allow-run-as-root --oversubscribe -np 2 "$kerf" run "$scene" --set solve.linear_solver=petsc \
  --set solve.duration=1000 --set "output.vtk={every: 2}" --out "$out" --quiet >"$out.log" 2>&1 &
launcher=$!
for _ in $(seq 600); do  # a few steps on disk first (at most a minute)
  [ -f "$out/probes.csv" ] && [ "$(wc -l <"$out/probes.csv")" -ge 6 ] && break
  sleep 0.1
done
[ -f "$out/probes.csv" ] && [ "$(wc -l <"$out/probes.csv")" -ge 6 ] || fail "the run did not get going"
# The ranks, by pid: mpirun's own children (Open MPI starts local ranks itself).
ranks=$(cat /proc/"$launcher"/task/*/children 2>/dev/null)
[ "$(wc -w <<<"$ranks")" -eq 2 ] || fail "mpirun has $(wc -w <<<"$ranks") children, expected the 2 ranks"
# Alive: the process exists and is not a zombie waiting to be reaped.
alive() { [ -r "/proc/$1/stat" ] && [ "$(cut -d')' -f2 "/proc/$1/stat" | cut -d' ' -f2)" != Z ]; }
for rank in $ranks; do alive "$rank" || fail "rank process $rank is not running before the signal"; done
kill -TERM "$launcher"
for _ in $(seq 300); do kill -0 "$launcher" 2>/dev/null || break; sleep 0.1; done
kill -0 "$launcher" 2>/dev/null && { kill -KILL "$launcher"; fail "still running 30 s after SIGTERM"; }
wait "$launcher"
code=$?
cat "$out.log"
[ "$code" -ne 0 ] || fail "mpirun exited 0"
for rank in $ranks; do alive "$rank" && fail "rank process $rank is still running"; done
grep -q '"status": "interrupted"' "$out/summary.json" || fail "summary.json does not say interrupted"
grep -q 'interrupted (SIGTERM)' "$out/summary.json" || fail "summary.json does not name SIGTERM"
last=$(grep -o 'file="[^"]*"' "$out/block_drop.pvd" | tail -1 | cut -d'"' -f2)
[ -n "$last" ] || fail "the collection lists no step"
pieces=$(grep -o 'Source="[^"]*"' "$out/$last" | cut -d'"' -f2)
[ "$(wc -w <<<"$pieces")" -eq 2 ] || fail "$last lists $(wc -w <<<"$pieces") pieces, expected 2"
for piece in $pieces; do
  tail -c 200 "$out/$piece" | grep -q '</VTKFile>' || fail "$piece is cut short"
done
echo "ok"
