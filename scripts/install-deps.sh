#!/usr/bin/env bash
# Installs every build, test and benchmark dependency of FaceSocial from Debian 12's archive.
# Idempotent: packages already present are left alone. Needs root or sudo.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ninja-build
  libopencv-dev libopencv-contrib-dev opencv-data
  libeigen3-dev libtbb-dev
  libbenchmark-dev libgtest-dev libgmock-dev googletest
  pybind11-dev python3-dev python3-numpy python3-pytest
  python3-matplotlib jupyter-nbconvert python3-nbformat python3-ipykernel
  nlohmann-json3-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
