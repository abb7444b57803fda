#!/usr/bin/env bash
# The demo: installs what is missing, builds Release, makes a procedural smoke plume with
# Mirage itself (no downloads) and renders assets/scenes/demo.toml — multiple scattering
# (volpath), a warm key sun, a sky dome, velocity motion blur — to out/demo.exr plus an sRGB
# preview out/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
pipeline/install-deps.sh
pipeline/build.sh build
mkdir -p out
[ -f assets/scenes/demo_smoke.vdb ] ||
  ./build/mirage make-asset smoke -o assets/scenes/demo_smoke.vdb --resolution 96 --seed 7
./build/mirage render assets/scenes/demo.toml -o out/demo.exr --preview out/demo.png
end=$(date +%s)
echo
echo "Demo rendered in $((end - start)) s (including install and build):"
echo "  scene-linear EXR (ACEScg): $PWD/out/demo.exr"
echo "  sRGB preview:              $PWD/out/demo.png"
