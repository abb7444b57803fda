#!/usr/bin/env bash
# The demo: installs what is missing, builds Release, makes a procedural fire-and-smoke plume with
# Mirage itself (no downloads) and renders assets/scenes/demo.toml — the flames scattered by
# their smoke, a low warm sun, a sky dome and a ground — to out/demo.exr plus an sRGB
# preview out/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
pipeline/install-deps.sh
pipeline/build.sh build
mkdir -p out
[ -f assets/scenes/demo_plume.vdb ] ||
  ./build/mirage make-asset plume -o assets/scenes/demo_plume.vdb --resolution 256 --seed 7
./build/mirage render assets/scenes/demo.toml -o out/demo.exr --preview out/demo.png
end=$(date +%s)
echo
echo "Demo rendered in $((end - start)) s (including install and build):"
echo "  scene-linear EXR (ACEScg): $PWD/out/demo.exr"
echo "  sRGB preview:              $PWD/out/demo.png"
