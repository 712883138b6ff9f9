#!/usr/bin/env bash
# Installs the Debian packages mpsolid needs, skipping what is already there.
# Run as root (or with sudo). Nothing is downloaded at build time.
set -euo pipefail
packages=(
  cmake g++ make git
  libeigen3-dev libnanoflann-dev libhdf5-dev libgtest-dev libbenchmark-dev
  libtoml11-dev libcli11-dev libfmt-dev nlohmann-json3-dev libboost-dev clang-format
  python3 python3-h5py python3-matplotlib
  python3-dev python3-numpy python3-setuptools python3-wheel python3-venv python3-pip pybind11-dev python3-pybind11
  libopenmpi-dev openmpi-bin
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
