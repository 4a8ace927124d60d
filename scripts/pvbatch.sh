#!/usr/bin/env bash
# pvbatch (Debian's paraview) offscreen under xvfb-run, with ParaView's Python
# modules that `make deps` unpacked under build/paraview-python
# (scripts/fetch_paraview_python.sh: nothing is downloaded here). Exits 77
# (ctest's SKIP_RETURN_CODE) when no X server can start, saying why.
# Usage: scripts/pvbatch.sh SCRIPT.py ARGS...
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
modules=${KERF_PARAVIEW_PYTHON:-$root/build/paraview-python}
if [ ! -d "$modules/usr/lib/python3/dist-packages/paraview" ]; then
  echo "pvbatch.sh: ParaView's Python modules are not in $modules; expected \`make deps\`" \
    "(or scripts/fetch_paraview_python.sh $modules) first"
  exit 1
fi
export PYTHONPATH="$modules/usr/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}"
command -v xvfb-run >/dev/null || { echo "pvbatch.sh: skipped: xvfb-run is not installed (package xvfb)"; exit 77; }
if ! why=$(xvfb-run -a -s "-screen 0 64x64x24" true 2>&1); then
  echo "pvbatch.sh: skipped: no X server can start here (xvfb-run: ${why:-no message})"
  exit 77
fi
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
