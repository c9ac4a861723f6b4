#!/usr/bin/env bash
# Installs the Debian 12 packages Upgrain needs. Skips the install when all are present.
set -euo pipefail
PACKAGES=(cmake g++ ninja-build ccache lld pkg-config
  libdeal.ii-dev libeigen3-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libcgal-dev libgmp-dev libmpfr-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-numpy python3-matplotlib python3-h5py
  clang libclang-rt-14-dev  # the libFuzzer targets (docs/input.md, "Fuzzing")
  strace)  # kills at a chosen system call in the fault tests (tests/end_to_end/check_output_safety.py)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
