#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs every build and test dependency from Debian's packages (Debian 12); the Python
# module's few from PyPI are scripts/python.sh's.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PKGS=(build-essential cmake ninja-build ccache pkg-config
      libcgal-dev libeigen3-dev libopenmesh-dev libflann-dev liblz4-dev
      libsuitesparse-dev libtbb-dev libtinyxml2-dev catch2 libcli11-dev python3 clang-format
      python3-dev python3-pip python3-pybind11 python3-numpy python3-pandas python3-pytest help2man)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
