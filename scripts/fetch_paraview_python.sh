#!/usr/bin/env bash
# ParaView's Python modules (python3-paraview) unpacked under DEST, for
# pvbatch (scripts/pvbatch.sh): on Debian 12 that package conflicts with
# python3-vtk9, which libvtk9-dev (kerf's build) needs, so it is extracted
# beside the build instead of installed. Run by `make deps`; does nothing
# when DEST already holds them.
# Usage: scripts/fetch_paraview_python.sh DEST
set -euo pipefail
dest=$1
[ -d "$dest/usr/lib/python3/dist-packages/paraview" ] && exit 0
mkdir -p "$dest"
cd "$dest"
download() { apt-get download python3-paraview >/dev/null 2>&1; }
if ! download; then  # a fresh machine's package lists may not know it yet
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  download || { echo "fetch_paraview_python: apt-get download python3-paraview failed" >&2; exit 1; }
fi
dpkg-deb -x python3-paraview_*.deb .
rm -f python3-paraview_*.deb
echo "fetch_paraview_python: ParaView's Python modules in $dest"
