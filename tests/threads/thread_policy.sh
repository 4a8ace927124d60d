#!/usr/bin/env bash
# kerf chooses its threads before libgomp loads (core/thread_policy.h) and
# says so in summary.json parallel.threads: as many as the cores it is given
# (all of them; one under `taskset -c 0`; one each for two unbound MPI ranks
# on this machine), waiting passively; a variable the user set is kept; a
# kerf started by kerf chooses its own instead of inheriting the parent's.
# usage: thread_policy.sh KERF SCENE OUT_DIR
set -u
kerf=$1 scene=$2 out=$3
rm -rf "$out"
mkdir -p "$out"
fail() { echo "FAILED: $*"; exit 1; }
cores=$(nproc --all)
threads() {  # threads DIR: "count wait_policy limited_by" from its summary
  python3 -c 'import json,sys; t=json.load(open(sys.argv[1]))["parallel"]["threads"]; print(t["count"], t["wait_policy"], t["limited_by"])' "$1/summary.json"
}
extra=()  # more arguments of `kerf run`
run() {  # run NAME [env and command prefix...]: runs the scene quietly into $out/NAME
  local name=$1; shift
  "$@" "$kerf" run "$scene" "${extra[@]}" --out "$out/$name" --quiet >"$out/$name.log" 2>&1 ||
    fail "$name: $(cat "$out/$name.log")"
}
clean=(env -u OMP_WAIT_POLICY -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT -u GOMP_SPINCOUNT -u KERF_THREAD_POLICY)

run plain "${clean[@]}"
read -r count wait limited <<<"$(threads "$out/plain")"
[ "$wait" = passive ] || fail "plain: wait policy $wait, expected passive"
if [ "$limited" = machine ]; then
  [ "$count" -eq "$cores" ] || fail "plain: $count threads on $cores cores"
else  # a container's quota or an inherited affinity
  [ "$count" -ge 1 ] && [ "$count" -le "$(nproc)" ] || fail "plain: $count threads, limited by $limited"
fi

if [ "$cores" -gt 1 ]; then
  run pinned "${clean[@]}" taskset -c 0
  [ "$(threads "$out/pinned")" = "1 passive affinity" ] || fail "taskset -c 0: $(threads "$out/pinned")"
fi

run users "${clean[@]}" OMP_WAIT_POLICY=active OMP_NUM_THREADS=1
read -r count wait limited <<<"$(threads "$out/users")"
[ "$count $wait" = "1 active" ] || fail "the user's variables: $count $wait"

# A kerf started by this one (as a study's point is): the parent's choice is
# recorded as kerf's, so the child chooses again under its own affinity.
marker="99999999|OMP_THREAD_LIMIT=$cores|OMP_NUM_THREADS=$cores|OMP_WAIT_POLICY=passive|limited_by=machine|"
if [ "$cores" -gt 1 ]; then
  run child "${clean[@]}" KERF_THREAD_POLICY="$marker" OMP_THREAD_LIMIT=$cores OMP_NUM_THREADS=$cores \
    OMP_WAIT_POLICY=passive taskset -c 0
  [ "$(threads "$out/child")" = "1 passive affinity" ] || fail "a child of kerf: $(threads "$out/child")"
fi

# Two MPI ranks on this machine, not bound: one thread each (rank 0 reports).
extra=(--set solve.linear_solver=petsc)
run ranks "${clean[@]}" mpirun --allow-run-as-root --oversubscribe --bind-to none -np 2
expected=$(( cores / 2 > 0 ? cores / 2 : 1 ))
read -r count wait limited <<<"$(threads "$out/ranks")"
[ "$count $wait" = "$expected passive" ] || fail "two unbound ranks: $count $wait $limited, expected $expected threads"
echo "ok"
