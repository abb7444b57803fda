#!/usr/bin/env bash
# Benchmarks (programs, not tests). Renders ../shared/data/vdb/smoke1.vdb single-scattered at
# 512×512 with Mirage and with OpenVDB's vdb_render at matched camera, light and coefficients,
# RUNS times each (default 3), and prints the medians and their ratio; then Mirage's NanoVDB
# lookup rates; the photon pass on smoke1 lit by a sun; beam against point estimate at equal
# error on the Cornell smoke scene; Cycles when installed. Needs ../shared/data (or
# MIRAGE_SHARED_DATA) and python3. Settings by environment: RUNS (3), SPP (16), PHOTONS (10^6,
# photon pass), CS_RES (64x64), CS_SPP (16), CS_PHOTONS (3e4,1e5,3e5,1e6), REF_SPP (1024).
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${MIRAGE_SHARED_DATA:-../shared/data}
SMOKE="$(realpath -m "$DATA/vdb/smoke1.vdb")"
if [ ! -f "$SMOKE" ]; then
  echo "bench: $SMOKE not found: the benchmark needs the reference data folder" >&2
  exit 1
fi
RUNS=${RUNS:-3}
SPP=${SPP:-16}
pipeline/install-deps.sh >/dev/null
pipeline/build.sh build >/dev/null
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

now() { date +%s.%N; }
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

: > "$TMP/vdb.txt"; : > "$TMP/mirage.txt"
for i in $(seq "$RUNS"); do
  t0=$(now)
  vdb_render "$SMOKE" "$TMP/vdb_render.exr" -res 512x512 -translate -7.4,60,190 \
    -lookat -7.4,40.5,0.5 -fov 40 -absorb 0.1,0.1,0.1 -scatter 1.5,1.5,1.5 \
    -light 0.3,0.3,0,1,1,1 -step 1 -shadowstep 3 -cpus 0 >/dev/null
  t1=$(now)
  ./build/mirage render tests/bench/smoke1_single.toml --set "volume.0.file=$SMOKE" \
    --spp "$SPP" -o "$TMP/mirage.exr" --quiet >/dev/null
  t2=$(now)
  awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}' >> "$TMP/vdb.txt"
  awk -v a="$t1" -v b="$t2" 'BEGIN {print b - a}' >> "$TMP/mirage.txt"
done
v=$(median < "$TMP/vdb.txt"); m=$(median < "$TMP/mirage.txt")
printf 'smoke1.vdb 512x512, single scattering, %d runs, %d cores\n' "$RUNS" "$(nproc)"
printf '  vdb_render (ray marching, step 1 voxel, shadow step 3): median %.2f s\n' "$v"
printf '  mirage (delta/ratio tracking, %d spp):                    median %.2f s\n' "$SPP" "$m"
printf '  ratio mirage / vdb_render: %.2f\n' "$(awk -v a="$m" -v b="$v" 'BEGIN {print a / b}')"
./build/tests/bench_lookups "$SMOKE"

# Photon pass throughput: assets/scenes/smoke1_sun.toml (smoke1, sun + sky fill) with
# PHOTONS photons (default 10^6), a tiny image so the render pass costs nothing; the figures are
# the renderer's own (EXR header mirage:photon_pass_seconds, mirage:photons_per_second).
PHOTONS=${PHOTONS:-1000000}
attr() { oiiotool --info -v "$1" | awk -v k="mirage:$2:" '$1 == k {gsub(/"/, "", $2); print $2}'; }
: > "$TMP/pass.txt"; : > "$TMP/rate.txt"
for i in $(seq "$RUNS"); do
  ./build/mirage render assets/scenes/smoke1_sun.toml --set "volume.0.file=$SMOKE" \
    --set "render.photons=$PHOTONS" --resolution 8x10 --spp 1 --seed "$i" \
    -o "$TMP/pass.exr" --quiet >/dev/null
  attr "$TMP/pass.exr" photon_pass_seconds >> "$TMP/pass.txt"
  attr "$TMP/pass.exr" photons_per_second >> "$TMP/rate.txt"
done
printf 'photon pass, smoke1.vdb + sun, %s photons, %d runs, %d cores\n' "$PHOTONS" "$RUNS" "$(nproc)"
printf '  median %.2f s, %.3g photons traced/s\n' "$(median < "$TMP/pass.txt")" "$(median < "$TMP/rate.txt")"

# Beam against point estimate at equal error on assets/scenes/cornell_smoke.toml: one volpath
# reference (REF_SPP), then both estimates over a photon sweep (CS_PHOTONS) at CS_SPP; the
# time each needs for the same relMSE is interpolated in log-log space (pipeline/equal_error.py).
CS_RES=${CS_RES:-64x64}
CS_SPP=${CS_SPP:-16}
CS_PHOTONS=${CS_PHOTONS:-3e4,1e5,3e5,1e6}
REF_SPP=${REF_SPP:-1024}
CS_DIR="$TMP/cornell"
mkdir -p "$CS_DIR"
cp assets/scenes/cornell_smoke.toml "$CS_DIR/"
./build/mirage make-asset fog-sphere -o "$CS_DIR/fog_sphere.vdb" >/dev/null
./build/mirage tradeoff "$CS_DIR/cornell_smoke.toml" --resolution "$CS_RES" --spp "$CS_SPP" \
  --integrator photon --vary "photons=$CS_PHOTONS" --vary estimate=beam,point \
  --reference-spp "$REF_SPP" -o "$CS_DIR/" --quiet >/dev/null
printf 'cornell_smoke.toml %s, %d spp, photons %s, volpath reference %d spp\n' "$CS_RES" \
  "$CS_SPP" "$CS_PHOTONS" "$REF_SPP"
sed 's/^/  /' "$CS_DIR/tradeoff.csv"
python3 pipeline/equal_error.py "$CS_DIR/tradeoff.csv"

# Peer check against Blender Cycles (when installed): same cache, camera, medium and sun,
# 64 spp at 256×256, single scattering (single vs Cycles with 0 volume bounces) and multiple
# scattering (volpath with max_depth 17 vs Cycles with 16 volume bounces). Prints both times,
# their ratio and the mean luminance and alpha of both images.
if command -v blender >/dev/null; then
  CYCLES_PY="$(dirname "$DATA")/tools/cycles_vdb.py"
  mean() { oiiotool --stats "$1" | awk '/Stats Avg/ {print 0.2126*$3 + 0.7152*$4 + 0.0722*$5; exit}'; }
  alpha() { oiiotool --stats "$1" | awk '/Stats Avg/ {print $6; exit}'; }
  for bounces in 0 16; do
    CYC=$(blender -b --factory-startup --python-exit-code 1 --python "$CYCLES_PY" -- \
      "$SMOKE" "$TMP/cycles.exr" 256 256 64 --density-scale 1 --albedo 0.9 --anisotropy 0 \
      --volume-bounces "$bounces" --sun-strength 5 --threads "$(nproc)" 2>&1 |
      awk '/RENDER_SECONDS/ {print $2}')
    integrator=single
    [ "$bounces" -gt 0 ] && integrator=volpath
    t0=$(now)
    ./build/mirage render tests/bench/smoke1_cycles.toml --set "volume.0.file=$SMOKE" \
      --set "render.integrator=$integrator" --set "render.max_depth=$((bounces + 1))" \
      -o "$TMP/mirage_cycles.exr" --quiet >/dev/null
    t1=$(now)
    mt=$(awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}')
    printf 'smoke1.vdb 256x256, 64 spp, %d volume bounces: Cycles against mirage --integrator %s\n' \
      "$bounces" "$integrator"
    printf '  cycles render %.2f s, mirage %.2f s, ratio mirage / cycles %.2f\n' "$CYC" "$mt" \
      "$(awk -v a="$mt" -v b="$CYC" 'BEGIN {print a / b}')"
    printf '  mean luminance: cycles %s, mirage %s; mean alpha: cycles %s, mirage %s\n' \
      "$(mean "$TMP/cycles.exr")" "$(mean "$TMP/mirage_cycles.exr")" \
      "$(alpha "$TMP/cycles.exr")" "$(alpha "$TMP/mirage_cycles.exr")"
  done
else
  echo "blender not installed: skipping the Cycles comparison (apt-get install blender)"
fi

# Curved light (docs/curved-light.md): end-point error and time of the Fermat path stepper,
# Dormand–Prince RK5(4)7M over tolerances 1e-3 … 1e-14 against forward Euler, on the linear
# profile with its exact path; writes out/bench/raypath.csv and two plots (~20 s).
./build/tests/bench_raypath out/bench
# "Model only what a scene requires": the grey path (σ wavelength-independent) against the
# forced spectral path on the same grey scene, volpath and photon pass, 1 thread, CPU time.
./build/tests/bench_grey_path
