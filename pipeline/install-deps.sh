#!/usr/bin/env bash
# Installs the Debian 12 packages Mirage needs, only those missing. Root or sudo.
# Usage: pipeline/install-deps.sh [fuzz]   "fuzz" adds clang 14 with its libFuzzer, ASan, UBSan
# and TSan runtimes (libclang-rt-14-dev) and llvm (llvm-symbolizer for readable sanitizer
# reports), which pipeline/fuzz.sh and pipeline/sanitize.sh need; the default build is g++.
# Blender is in the default set: it hosts the Mirage add-on (src/blender), whose tests (label
# blender) pipeline/test.sh runs, and its Cycles is the peer pipeline/race.sh races against
# (a 50 MB download; the argument "blender" of earlier versions is still accepted). xvfb and
# Mesa's software OpenGL (libgl1-mesa-dri) run its viewport test with a window, headless.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config ccache
  libopenvdb-dev libnanovdb-dev libboost-iostreams-dev libblosc-dev zlib1g-dev libopenvdb-tools
  libopenvdb-ax-dev
  libembree-dev libtinyobjloader-dev
  libopenimageio-dev openimageio-tools fonts-dejavu-core
  libopencolorio-dev opencolorio-tools
  libopenexr-dev libimath-dev openexr
  libtbb-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev
  python3 python3-dev pybind11-dev python3-numpy python3-pytest python3-openvdb
  blender xvfb libgl1-mesa-dri
)
if [ "${1:-}" = "fuzz" ]; then
  PACKAGES+=(clang clang-14 libclang-rt-14-dev llvm)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
