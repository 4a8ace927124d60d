#!/usr/bin/env bash
# The main job (`make run`): runs every example scene and prints where the
# results are. The studies (issue 5) will be added here as they arrive.
set -euo pipefail
build=${1:-build}
cd "$(dirname "$0")/.."
kerf="$build/app/kerf"
mkdir -p results
for scene in scenes/*.yaml; do
  name=$(basename "$scene" .yaml)
  echo "== $name"
  "$kerf" run "$scene" --out "results/scenes/$name"
done
echo
echo "Results: results/scenes/<scene>/summary.json, probes.csv, and <scene>.pvd to open in ParaView."
