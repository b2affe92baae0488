#!/usr/bin/env bash
# Shared by test.sh and demo.sh: install the Debian packages hvi needs (skipping those already
# installed), then configure and build a Release build in build/.
set -euo pipefail

HVI_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
HVI_BUILD="${HVI_BUILD:-$HVI_ROOT/build}"

packages=(
  cmake make g++ git pkg-config clang-format
  libtomlplusplus-dev libcli11-dev libfmt-dev libhdf5-dev libeigen3-dev libcgal-dev
  libhdf5-openmpi-dev  # the ranks of one run write each snapshot together (parallel HDF5)
  libgtest-dev libgmock-dev libbenchmark-dev
  libdeal.ii-dev  # the finite-element far field (fem/): deal.II 9.4
  openmpi-bin libopenmpi-dev  # mpirun -np N hvi sweep (parallel/), and its tests
  libboost-dev  # Boost.Math's students_t (header-only) for hvi fit's significance tests
  python3 python3-numpy python3-h5py python3-matplotlib
)

install_packages() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "hvi: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# HVI_BUILD_TYPE (default Release), HVI_CMAKE_ARGS and HVI_BUILD_TARGETS (default all) pick
# another build: test_sanitizers.sh.
build_hvi() {
  # shellcheck disable=SC2086
  cmake -S "$HVI_ROOT" -B "$HVI_BUILD" -DCMAKE_BUILD_TYPE="${HVI_BUILD_TYPE:-Release}" \
    ${HVI_CMAKE_ARGS:-} >/dev/null
  # shellcheck disable=SC2086
  cmake --build "$HVI_BUILD" --parallel "$(nproc)" --target ${HVI_BUILD_TARGETS:-all}
}

install_packages
build_hvi
