#!/usr/bin/env bash
# pvbatch (Debian's paraview) offscreen under xvfb-run, with ParaView's Python
# modules from python3-paraview unpacked under build/paraview-python: on
# Debian 12 that package conflicts with python3-vtk9, which libvtk9-dev (kerf's
# build) needs, so it is extracted beside the build instead of installed.
# Usage: scripts/pvbatch.sh SCRIPT.py ARGS...
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
modules=${KERF_PARAVIEW_PYTHON:-$root/build/paraview-python}
if [ ! -d "$modules/usr/lib/python3/dist-packages/paraview" ]; then
  mkdir -p "$modules"
  (cd "$modules" && apt-get download python3-paraview >/dev/null 2>&1 && dpkg-deb -x python3-paraview_*.deb . &&
    rm -f python3-paraview_*.deb) || { echo "pvbatch.sh: could not fetch python3-paraview (apt-get download)"; exit 1; }
fi
export PYTHONPATH="$modules/usr/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}"
# xvfb-run's server is sometimes not ready for pvbatch's first connection
# (seen once under ctest -j2: "bad X server connection", SIGABRT): a second
# server is tried then, once; any other failure is pvbatch's own.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for attempt in 1 2; do
  status=0
  xvfb-run -a -s "-screen 0 1280x1024x24" pvbatch "$@" 2>&1 | tee "$log" || status=$?
  grep -q "bad X server connection" "$log" || exit "$status"
  echo "pvbatch.sh: the X server was not ready (attempt $attempt)"
done
exit 1
