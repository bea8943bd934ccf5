#!/usr/bin/env bash
# Installs the Debian packages spp needs (Debian 12, as root). Skips apt entirely when all are present.
set -euo pipefail
PACKAGES=(g++ cmake ninja-build pkg-config
          libeigen3-dev libopenblas-pthread-dev nlohmann-json3-dev libcli11-dev libspectra-dev libsuitesparse-dev
          libgtest-dev googletest libbenchmark-dev
          python3 python3-dev python3-pip python3-venv pybind11-dev python3-numpy python3-pytest
          python3-matplotlib python3-pil python3-pandas python3-siconos
          python3-nbclient python3-nbformat python3-ipykernel python3-tqdm
          openmpi-bin libopenmpi-dev python3-mpi4py)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "spp: installing Debian packages: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
