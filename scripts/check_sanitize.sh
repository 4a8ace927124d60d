#!/usr/bin/env bash
# `make check-sanitize`: builds kerf with AddressSanitizer and
# UndefinedBehaviorSanitizer (GCC, -O1 -g; build-sanitize) and runs the unit,
# regression and malformed-input tests under them. Any report stops the test
# that met it (halt_on_error); leaks in the libraries kerf calls (Open MPI,
# PETSc, VTK, gmsh) are suppressed by tests/sanitize/lsan.supp, kerf's own are not.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-sanitize
"$root/scripts/install_deps.sh" || exit 1
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DKERF_SANITIZE=ON >/dev/null || exit 1
cmake --build "$build" -j 2 || exit 1
# Exact stacks for leaks (the fast unwinder loses them in Open MPI, whose
# leaks at exit the suppressions then cannot match).
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:fast_unwind_on_malloc=0
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$root/tests/sanitize/lsan.supp:print_suppressions=0
# Left out: malformed.mesh_gmsh_bad_alloc, where gmsh's reader meets an
# allocation it cannot have: under ASan operator new aborts instead of
# throwing std::bad_alloc (the run then says gmsh crashed, not bad_alloc).
cd "$build" && ctest --output-on-failure -j 2 -R "^(unit|regression|malformed)\." -E "mesh_gmsh_bad_alloc" \
  --timeout 1200
