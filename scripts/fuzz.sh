#!/usr/bin/env bash
# `make fuzz`: builds the libFuzzer targets with clang-16 (every kerf file
# instrumented, AddressSanitizer + UndefinedBehaviorSanitizer) in build-fuzz
# and runs each for FUZZ_SECONDS (default 600) from a seed corpus of the
# example and malformed scenes and meshes. The corpus grows in
# build-fuzz/corpus/<target> across runs; a crash, hang (10 s), leak or
# sanitizer report leaves its input in build-fuzz/artifacts/<target>/ and
# fails the target. Prints each target's executions and rate. Allocations
# that cannot be served throw std::bad_alloc, as in a release build, so an
# input asking for terabytes is a refusal, not a finding.
set -uo pipefail
seconds=${1:-${FUZZ_SECONDS:-600}}
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-fuzz
"$root/scripts/install_deps.sh" clang-16 libfuzzer-16-dev libclang-rt-16-dev libomp-16-dev || exit 1
CC=clang-16 CXX=clang++-16 cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DKERF_FUZZ=ON >/dev/null || exit 1
cmake --build "$build" -j 2 --target fuzz_scene fuzz_msh || exit 1

seed() {  # seed TARGET FILES...: copies the seeds into the target's corpus
  local corpus=$build/corpus/$1
  shift
  mkdir -p "$corpus"
  cp -n "$@" "$corpus"/ 2>/dev/null || true
}
seed fuzz_scene "$root"/scenes/*.yaml "$root"/tests/malformed/*.yaml
seed fuzz_msh "$root"/scenes/meshes/*.msh "$root"/tests/malformed/meshes/*.msh "$root"/tests/fuzz/msh_seeds/*.msh

failed=0
for target in fuzz_scene fuzz_msh; do
  mkdir -p "$build/artifacts/$target"
  # fuzz_scene: a scene key dictionary; 10 s a unit, 4 GB. fuzz_msh: kerf's
  # own reader runs in this process; a unit it leaves to gmsh forks gmsh's
  # reader (read_msh), whose allocations libFuzzer's own
  # limits would report as crashes of this process (the child is a copy of
  # it): ASan caps one allocation at 4 GB instead (std::bad_alloc in the
  # child, reported by kerf), and a unit may take read_msh's 60 s deadline.
  options=(-dict="$root/tests/fuzz/scene.dict" -timeout=10 -rss_limit_mb=4096)
  [ "$target" = fuzz_msh ] && options=(-timeout=90 -rss_limit_mb=0 -malloc_limit_mb=0)
  echo "== $target: $seconds s from $(ls "$build/corpus/$target" | wc -l) inputs"
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1:max_allocation_size_mb=4096 \
    "$build/tests/fuzz/$target" "$build/corpus/$target" "${options[@]}" \
    -max_total_time="$seconds" -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/$target/" 2>"$build/$target.log"
  code=$?
  grep -E "^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)|^#[0-9]+.*DONE" "$build/$target.log"
  echo "   corpus now $(ls "$build/corpus/$target" | wc -l) inputs; exit $code; log $build/$target.log"
  [ "$code" -eq 0 ] || { failed=1; tail -40 "$build/$target.log"; }
done
exit $failed
