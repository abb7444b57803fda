#!/usr/bin/env bash
# Configures and builds Mirage. Usage: pipeline/build.sh [BUILD_DIR] [extra cmake args…]
# Environment: MIRAGE_BUILD_TYPE (default Release), MIRAGE_JOBS (default: cores).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${1:-build}
shift || true
JOBS=${MIRAGE_JOBS:-$(nproc)}
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE="${MIRAGE_BUILD_TYPE:-Release}" "$@" >/dev/null
ninja -C "$BUILD_DIR" -j "$JOBS"
