#!/usr/bin/env bash
# The main job (`make run`): every example scene, then every study in its
# quick mode, into results/main_job/; writes results/main_job/README.md (the
# headline figures and the plots) and prints where to look.
set -euo pipefail
build=${1:-build}
cd "$(dirname "$0")/.."
kerf="$build/cli/kerf"
out=results/main_job
mkdir -p "$out/scenes"
for scene in scenes/*.yaml; do
  name=$(basename "$scene" .yaml)
  echo "== scene $name"
  "$kerf" run "$scene" --out "$out/scenes/$name" --quiet
done
for study in $("$kerf" study | awk '/^  /{print $1}'); do
  echo "== study $study"
  "$kerf" study "$study" --quick --out "$out/$study"
done
echo "== pictures of the cut block (ParaView)"
status=0
KERF_PARAVIEW_PYTHON="$build/paraview-python" scripts/pvbatch.sh scripts/paraview_pictures.py "$out/cut" \
  "$out/pictures" >"$out/pictures.log" 2>&1 || status=$?
grep -vE "^\s*$|Could not determine" "$out/pictures.log" || true
# 77: no X server here (pvbatch.sh said why): the README goes without pictures.
[ "$status" -eq 0 ] || [ "$status" -eq 77 ] || exit "$status"
readme=$(/usr/bin/python3 scripts/headline_table.py "$out")
echo
echo "Headline figures and plots: $readme"
echo "ParaView: $out/scenes/<scene>/<scene>.pvd, the cut study's $out/cut/runs/<way>/cut.pvd; every run's"
echo "summary.json beside it."
echo "Full study results (committed), per question: results/README.md"
