#!/usr/bin/env bash
# The race against Blender Cycles on ../shared/data/vdb/smoke1.vdb (tests/bench/smoke1_race.toml:
# σt = 5 per unit density, albedo 0.95, isotropic, the sun, 256×256, a 1-px box filter on both
# sides). Each renderer is measured against its own converged image (REF_SPP samples, kept in
# OUT between runs: Cycles' ray marching and Mirage's tracking converge to slightly different
# images), by relMSE over the smoke's pixels (pipeline/relmse.py), at each of SPPS.
#   single    Cycles with 0 volume bounces against mirage --integrator single
#   multiple  Cycles with 64 volume bounces against mirage --integrator volpath, Mirage's
#             default (integrator auto at the same spp: what `mirage render` does unasked), and
#             the progressive photon mapper (--integrator photon --passes P, one photon map per
#             pass), all against the same volpath reference: a biased method's bias counts,
#             and a render in passes is timed by mirage:time_spent, its photon passes included;
#             and Mirage given only a time (`mirage render --time-limit T`, the rows "mirage
#             timed", whose spp column holds T): below one full pass that is the coarse image.
# Usage: pipeline/race.sh [single | multiple | both]   (default single)
# Other caches: CACHE=path.vdb races that file's `density` grid instead of smoke1, with the same
# medium, sun and resolution, and the camera cycles_vdb.py frames it with (read from its
# CYCLES_VDB line and handed to Mirage by --set); outputs are named after the cache.
# Environment: CACHE, SPPS ("4 16 64"), REF_SPP (1024), THREADS (2), OUT (out/race), SAMPLERS
# ("sobol random": Mirage's [render] sampler values raced; "default" sets none), MIRAGE
# (build/mirage: another build to race, e.g. an older one against the same references),
# PHOTON_PASSES ("2 8 24": pass counts of the photon rows; "" for none), PHOTONS (100000:
# photons per pass), PASS_SPP (4: samples per pixel per pass), TIME_LIMITS ("0.03 0.1 0.3 1 3":
# seconds of the timed rows; "" for none), MIRAGE_SHARED_DATA.
# Installs Blender when missing (pipeline/install-deps.sh blender). Prints one table per mode (also
# OUT/<cache>.<integrator>.csv) and the equal-error time ratios.
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${MIRAGE_SHARED_DATA:-../shared/data}
SMOKE="$(realpath -m "${CACHE:-$DATA/vdb/smoke1.vdb}")"
NAME=$(basename "$SMOKE" .vdb)
CYCLES_PY="$(realpath -m "$DATA/../tools/cycles_vdb.py")"
for f in "$SMOKE" "$CYCLES_PY"; do
  [ -f "$f" ] || { echo "race: $f not found: the race needs the reference data folder" >&2; exit 1; }
done
MODE=${1:-single}
case "$MODE" in single | multiple | both) ;; *) echo "race: expected single, multiple or both" >&2; exit 1 ;; esac
SPPS=${SPPS:-4 16 64}
REF_SPP=${REF_SPP:-1024}
THREADS=${THREADS:-2}
OUT=${OUT:-out/race}
SAMPLERS=${SAMPLERS:-sobol random}
PHOTON_PASSES=${PHOTON_PASSES-2 8 24}
PHOTONS=${PHOTONS:-100000}
PASS_SPP=${PASS_SPP:-4}
TIME_LIMITS=${TIME_LIMITS-0.03 0.1 0.3 1 3}
MIRAGE=${MIRAGE:-build/mirage}
command -v blender >/dev/null || pipeline/install-deps.sh blender >/dev/null
[ -x build/mirage ] || pipeline/build.sh build >/dev/null
mkdir -p "$OUT"

# The camera Cycles frames the cache with (cycles_vdb.py's CYCLES_VDB line of a 1-spp probe,
# kept in OUT), as Mirage's --set arguments: the race scene's own camera is smoke1's.
CAMERA_FILE="$OUT/$NAME.camera"
if [ ! -s "$CAMERA_FILE" ]; then
  blender -b --factory-startup --python-exit-code 1 --python "$CYCLES_PY" -- "$SMOKE" \
    "$OUT/$NAME.probe.exr" 256 256 1 --density-scale 5 --threads "$THREADS" 2>&1 |
    python3 -c '
import re, sys
for line in sys.stdin:
    m = re.search(r"camera_pos \(([^)]*)\) look_at \(([^)]*)\) .* fov_deg ([0-9.]+)", line)
    if m:
        print("camera.position=[%s]" % m.group(1).replace(" ", ""))
        print("camera.look_at=[%s]" % m.group(2).replace(" ", ""))
        print("camera.fov=%s" % m.group(3))
' >"$CAMERA_FILE"
  rm -f "$OUT/$NAME.probe.exr"
  [ -s "$CAMERA_FILE" ] || { echo "race: no camera from cycles_vdb.py for $SMOKE" >&2; exit 1; }
fi
CAMERA=()
while read -r kv; do CAMERA+=(--set "$kv"); done <"$CAMERA_FILE"

# References take another seed (7): with a low-discrepancy sampler, their first samples would
# otherwise be the very samples of the images they judge.
# Cycles: prints its render seconds (scene set-up excluded).
cycles() {  # bounces spp exr [seed]
  blender -b --factory-startup --python-exit-code 1 --python "$CYCLES_PY" -- "$SMOKE" "$3" \
    256 256 "$2" --density-scale 5 --albedo 0.95 --anisotropy 0 --volume-bounces "$1" \
    --sun-strength 5 --threads "$THREADS" --pixel-filter box --seed "${4:-0}" 2>&1 |
    awk '/RENDER_SECONDS/ {print $2}'
}
# Mirage: prints its frame seconds (mirage:frame_seconds: the integrator's set-up, such as
# single scattering's light guide, and the render; loading and writing excluded).
mirage() {  # integrator sampler spp exr [seed]
  local sampler=()
  [ "$2" = default ] || sampler=(--set "render.sampler=$2")
  "$MIRAGE" render tests/bench/smoke1_race.toml --set "volume.0.file=$SMOKE" "${CAMERA[@]}" \
    --set "render.integrator=$1" "${sampler[@]}" --spp "$3" --threads "$THREADS" \
    --seed "${5:-0}" -o "$4" --quiet >/dev/null
  oiiotool --info -v "$4" | awk -F'"' '/mirage:frame_seconds/ {print $2}'
}

# Mirage's progressive photon mapper in P passes: prints the seconds since the frame began
# (mirage:time_spent: integrator set-up and every pass's photon map included).
photon() {  # passes exr
  "$MIRAGE" render tests/bench/smoke1_race.toml --set "volume.0.file=$SMOKE" "${CAMERA[@]}" \
    --integrator photon --set "render.photons=$PHOTONS" --set "render.pass_spp=$PASS_SPP" \
    --passes "$1" --threads "$THREADS" --seed 0 -o "$2" --quiet >/dev/null
  oiiotool --info -v "$2" | awk -F'"' '/mirage:time_spent/ {print $2}'
}

# Mirage as a user runs it: the default integrator at the scene's settings and ARGS, such as
# `--spp N` (on dense smoke, progressive photon passes) or `--time-limit T` (below one full
# pass, the coarse image). Prints mirage:time_spent for a render in passes (what a time limit
# is compared with), else mirage:frame_seconds.
default_render() {  # exr args...
  local exr=$1
  shift
  "$MIRAGE" render tests/bench/smoke1_race.toml --set "volume.0.file=$SMOKE" "${CAMERA[@]}" \
    --set render.integrator=auto "$@" --threads "$THREADS" --seed 0 -o "$exr" --quiet >/dev/null
  oiiotool --info -v "$exr" |
    awk -F'"' '/mirage:time_spent/ {t = $2} /mirage:frame_seconds/ {f = $2} END {print (t != "" ? t : f)}'
}

race() {  # bounces integrator
  local bounces=$1 integrator=$2 tag="$OUT/$NAME.$2"
  printf '\n%s.vdb 256x256, %d threads: Cycles --volume-bounces %d against mirage --integrator %s\n' \
    "$NAME" "$THREADS" "$bounces" "$integrator"
  [ -f "$tag.cycles_ref.exr" ] || cycles "$bounces" "$REF_SPP" "$tag.cycles_ref.exr" 7 >/dev/null
  [ -f "$tag.mirage_ref.exr" ] || mirage "$integrator" sobol "$REF_SPP" "$tag.mirage_ref.exr" 7 >/dev/null
  printf '  %-5s %-16s %8s %10s\n' spp renderer seconds relMSE
  echo "renderer,spp,seconds,relmse" > "$tag.csv"
  row() {  # renderer spp seconds image reference
    local e
    e=$(python3 pipeline/relmse.py "$4" "$5")
    printf '  %-5s %-16s %8.2f %10.4g\n' "$2" "$1" "$3" "$e"
    echo "$1,$2,$3,$e" >> "$tag.csv"
  }
  for spp in $SPPS; do
    row cycles "$spp" "$(cycles "$bounces" "$spp" "$tag.cycles.exr")" "$tag.cycles.exr" \
      "$tag.cycles_ref.exr"
    for sampler in $SAMPLERS; do
      row "mirage $sampler" "$spp" "$(mirage "$integrator" "$sampler" "$spp" "$tag.mirage.exr")" \
        "$tag.mirage.exr" "$tag.mirage_ref.exr"
    done
  done
  # Multiple scattering: the default and the progressive photon mapper against the same
  # volpath reference.
  if [ "$integrator" = volpath ]; then
    for spp in $SPPS; do
      row "mirage default" "$spp" "$(default_render "$tag.default.exr" --spp "$spp")" \
        "$tag.default.exr" "$tag.mirage_ref.exr"
    done
    for limit in $TIME_LIMITS; do
      row "mirage timed" "$limit" "$(default_render "$tag.timed.exr" --time-limit "$limit")" \
        "$tag.timed.exr" "$tag.mirage_ref.exr"
    done
    for passes in $PHOTON_PASSES; do
      row "mirage photon" "$((passes * PASS_SPP))" "$(photon "$passes" "$tag.photon.exr")" \
        "$tag.photon.exr" "$tag.mirage_ref.exr"
    done
  fi
  # Equal error: each Mirage's time to Cycles' relMSE at each spp (pipeline/race_ratio.py).
  python3 pipeline/race_ratio.py "$tag.csv"
}

[ "$MODE" = multiple ] || race 0 single
[ "$MODE" = single ] || race 64 volpath
