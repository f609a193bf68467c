#!/usr/bin/env bash
# The single place that lists the Debian packages frictopt needs (build, tests, benchmarks,
# pictures). Idempotent and non-interactive; run as root (or via sudo when available).
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libsuitesparse-dev libblas-dev liblapack-dev libopenblas0-pthread libceres-dev libvtk9-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libtomlplusplus-dev libfmt-dev nlohmann-json3-dev
  libfclib-dev libhdf5-dev
  libgmsh-dev gmsh python3-gmsh
  python3 python3-numpy python3-matplotlib python3-vtk9 xvfb xauth
  python3-siconos python3-h5py python3-scipy
  pybind11-dev python3-dev python3-pytest
  petsc-dev openmpi-bin
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
