#!/usr/bin/env bash
# Installs the Debian packages rotbeam needs, only those missing. Uses sudo only when not root.
set -euo pipefail

packages=(
  cmake g++ make
  libeigen3-dev libboost-dev libtomlplusplus-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libbenchmark-dev
  pybind11-dev python3-pybind11 python3-dev python3-numpy python3-matplotlib python3-pil python3-pytest
  python3-xarray python3-netcdf4 python3-distributed
  python3-pip python3-setuptools python3-wheel python3-venv
  clang libclang-rt-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "installing: ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  as_root=()
else
  as_root=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
