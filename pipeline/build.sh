#!/usr/bin/env bash
# Configures and builds Mirage. Usage: pipeline/build.sh [BUILD_DIR] [extra cmake args…]
# Environment: MIRAGE_BUILD_TYPE (default Release), MIRAGE_JOBS (default: cores).
# ccache, when installed, caches compiles: an OpenVDB translation unit costs ~28 s, and a
# rebuild after switching branches or build directories then costs seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${1:-build}
shift || true
JOBS=${MIRAGE_JOBS:-$(nproc)}
LAUNCHER=()
if command -v ccache >/dev/null; then
  LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}  # paths under the checkout hashed relative: a worktree hits
fi
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE="${MIRAGE_BUILD_TYPE:-Release}" "${LAUNCHER[@]}" "$@" >/dev/null
ninja -C "$BUILD_DIR" -j "$JOBS"
