#!/usr/bin/env bash
# Installs the Debian packages kerf builds and runs with, and any named as
# arguments (make fuzz: clang's); does nothing when all are present.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libsuitesparse-dev libopenblas0-openmp petsc-dev mpi-default-dev libcgal-dev
  libgmsh-dev gmsh libvtk9-dev libyaml-cpp-dev nlohmann-json3-dev libnanoflann-dev
  libgtest-dev libbenchmark-dev
  python3-numpy python3-matplotlib python3-dev pybind11-dev python3-pytest
  paraview xvfb xauth calculix-ccx
  "$@"
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
