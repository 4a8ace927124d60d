#!/usr/bin/env bash
# `cmake --install` into a fresh prefix, then examples/user_material
# configured with only that prefix (no kerf source or build tree on its
# paths), built, and its own tests run: a law registered outside kerf, used
# by a scene, checked against kerf's neo-Hookean.
# Usage: example_project.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
source_dir=$1 build_dir=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build_dir" --prefix "$work/prefix" >"$work/install.log"
test -x "$work/prefix/bin/kerf" || { echo "no bin/kerf in the prefix"; exit 1; }
"$work/prefix/bin/kerf" --version
# The Python package from the prefix alone (not the build tree's).
(cd "$work" && PYTHONPATH="$work/prefix/lib/python3/dist-packages" /usr/bin/python3 -c \
  "import kerf, sys; assert kerf.__file__.startswith('$work/prefix/'), kerf.__file__; print('python: kerf', kerf.__version__)")
# Its modules (gmsh, VTK) from the prefix too, when a run needs them.
(cd "$work" && PYTHONPATH="$work/prefix/lib/python3/dist-packages" /usr/bin/python3 - \
  "$source_dir/scenes/plate_tension_2d.yaml" "$work/python_out" "$work/prefix/" <<'PY'
import kerf, sys
kerf.run(sys.argv[1], out=sys.argv[2])
maps = open("/proc/self/maps").read().splitlines()
for module in ("libkerf_gmsh.so", "libkerf_vtk.so"):
    paths = {line.split()[-1] for line in maps if line.endswith(module)}
    assert paths and all(p.startswith(sys.argv[3]) for p in paths), f"{module} loaded from {paths}"
print("python: the modules from the prefix")
PY
)
# Only the public headers and what they include are installed (cmake/public_headers.cmake):
# a body's own header is not there, and every installed header compiles from the prefix alone.
headers="$work/prefix/include/kerf"
test -f "$headers/problem/user_material.h" || { echo "no public header problem/user_material.h installed"; exit 1; }
test ! -e "$headers/discretization/meshless/nodal_body.h" || { echo "an internal header was installed"; exit 1; }
mkdir -p "$work/headers"
(cd "$headers" && find . -name '*.h' | sed 's|^\./|#include "|; s|$|"|') >"$work/headers/all_headers.cpp"
echo "installed headers: $(wc -l <"$work/headers/all_headers.cpp")"
cat >"$work/headers/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(kerf_headers LANGUAGES C CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(kerf REQUIRED)
add_library(all_headers OBJECT all_headers.cpp)
target_link_libraries(all_headers PRIVATE kerf::cli)
CMAKE
cmake -S "$work/headers" -B "$work/headers/build" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON >"$work/headers.log" 2>&1 &&
  cmake --build "$work/headers/build" >>"$work/headers.log" 2>&1 || { tail -40 "$work/headers.log"; exit 1; }
cmake -S "$source_dir/examples/user_material" -B "$work/example" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON >"$work/configure.log" ||
  { cat "$work/configure.log"; exit 1; }
grep -q "kerf_DIR:PATH=$work/prefix/" "$work/example/CMakeCache.txt" ||
  { echo "find_package(kerf) found another kerf: $(grep kerf_DIR "$work/example/CMakeCache.txt")"; exit 1; }
cmake --build "$work/example" -j 2 >"$work/build.log" 2>&1 || { tail -40 "$work/build.log"; exit 1; }
cd "$work/example" && ctest --output-on-failure -V 2>&1 | grep -E "tip z|tests passed|Failed|\*\*\*|Error|error" 
ctest --output-on-failure >/dev/null
# examples/session_loop: a program stepping a kerf session from its own loop, built from the prefix alone,
# gives `kerf run`'s probes to the last digit on the installed organ_cut scene (a cut growing as it sags).
cmake -S "$source_dir/examples/session_loop" -B "$work/session_loop" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON >"$work/session_configure.log" ||
  { cat "$work/session_configure.log"; exit 1; }
cmake --build "$work/session_loop" -j 2 >"$work/session_build.log" 2>&1 || { tail -40 "$work/session_build.log"; exit 1; }
organ="$work/prefix/share/kerf/scenes/organ_cut.yaml"
"$work/session_loop/kerf_session_loop" "$organ" "$work/session_out" solve.duration=0.08 | tail -2
"$work/prefix/bin/kerf" run "$organ" --quiet --out "$work/batch_out" --set solve.duration=0.08
python3 - "$work/session_out/summary.json" "$work/batch_out/summary.json" <<'CHECK'
import json, sys
session, batch = (json.load(open(path)) for path in sys.argv[1:])
assert session["status"] == "ok", session["status"]
if session["probes"] != batch["probes"]:
    sys.exit(f"the session loop's probes {session['probes']} differ from kerf run's {batch['probes']}")
print("session loop: kerf run's probes to the last digit")
CHECK
