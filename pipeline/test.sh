#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test with ctest: unit tests and the slower
# physics checks (label "physics"); not the gallery's noise check (label "gallery", minutes:
# `cd build && ctest -L gallery`). Extra arguments go to ctest (e.g. -L unit).
set -euo pipefail
cd "$(dirname "$0")/.."
pipeline/install-deps.sh
pipeline/build.sh build
cd build
ctest --output-on-failure --timeout 900 -j "$(nproc)" -LE gallery "$@"  # ctest -L gallery: the noise check
