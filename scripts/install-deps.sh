#!/usr/bin/env bash
# Installs the Debian 12 packages tirefe needs to build, test and plot.
# Idempotent: does nothing (quietly) when everything is already installed.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libsuitesparse-dev liblua5.4-dev libhdf5-dev catch2
  hdf5-tools python3-h5py python3-matplotlib python3-numpy python3-meshio
  libopenmpi-dev openmpi-bin
  pybind11-dev python3-pybind11 python3-scipy
  clang-format
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "tirefe: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
