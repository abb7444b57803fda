#!/usr/bin/env bash
# The race against Blender Cycles (docs/performance.md, "The race against Cycles at equal error";
# the regime suite: docs/regimes.md). Each renderer is measured against its own converged image
# (REF_SPP samples, another seed, kept in OUT between runs: Cycles' ray marching and Mirage's
# tracking converge to slightly different images), by relMSE over the medium's pixels
# (pipeline/relmse.py), on 2 threads with a 1-px box filter on both sides.
#
# Usage: pipeline/race.sh [single | multiple | both]   the race on smoke1 (default single):
#   single    Cycles with 0 volume bounces against mirage --integrator single
#   multiple  Cycles with 64 volume bounces against mirage --integrator volpath, Mirage's
#             default (integrator auto at the same spp: what `mirage render` does unasked), and
#             the progressive photon mapper (--integrator photon --passes P, one photon map per
#             pass), all against the same volpath reference: a biased method's bias counts,
#             and a render in passes is timed by mirage:time_spent, its photon passes included;
#             and Mirage given only a time (`mirage render --time-limit T`, the rows "mirage
#             timed", whose spp column holds T): below one full pass that is the coarse image.
#   (tests/bench/smoke1_race.toml: σt = 5 per unit density, albedo 0.95, isotropic, the sun,
#   256×256.) Other caches: CACHE=path.vdb races that file's `density` grid instead of smoke1,
#   with the same medium, sun and resolution, and the camera cycles_vdb.py frames it with;
#   outputs are named after the cache (OUT/<cache>.<integrator>.csv).
# Usage: pipeline/race.sh REGIME | all | check   one regime of the suite, or every one in turn,
# or (check) every regime's scene loaded and held against its Cycles options, racing nothing:
#   sun         the race above in its multiple mode (smoke1_race.toml)
#   sky-white   a bright forward-scattering cloud under a constant white dome
#   sky-hdr     the same cloud under a lat-long HDR sky with a small sun (pipeline/sky_hdr.py)
#   lamp-point  a point light inside thin-to-medium smoke
#   lamp-spot   a spot light there
#   lamp-sphere a sphere light there (radius 2 m; Cycles' a point light at its centre)
#   fire        fire lighting its own smoke by blackbody emission
#   haze        thin haze, a spot light's beam seen from the side
#   Each regime is one scene, tests/bench/race_<regime>.toml (the sun's smoke1_race.toml), whose
#   comment says what it is and why its parameters, and whose `# race.*` lines give the cache,
#   Cycles' medium and lights, the volume bounces, the Mirage rows and the time limits. Rows:
#   Cycles at each of SPPS; Mirage's default given samples ("mirage default", --spp) and given
#   a time ("mirage timed", --time-limit; the spp column holds the limit); the rows the scene
#   names (volpath, single: by samples; photon: progressive passes), all against the volpath
#   reference. Outputs OUT/<regime>.csv, the plot OUT/<regime>.png (pipeline/race_plot.py), the
#   references' previews OUT/<regime>.{cycles,mirage}_ref.png, the run's date, machine and
#   load (OUT/<regime>.run.txt), the bounce check (OUT/<regime>.bounces.txt: Cycles' mean at
#   its bounces and at 4×, and the reference's cut Mirage paths) and, where the scene asks
#   (`# race.checks = seeds mean`), OUT/<regime>.checks.txt: the noise between two seeds at
#   CHECK_SPP of Mirage's default and of Cycles, and the mean of a MEAN_SECONDS default render
#   against the volpath reference. pipeline/race_summary.py OUT prints the regime table.
# Environment: CACHE, SPPS ("4 16 64"), LOW_SPPS ("1 2": Mirage's default alone, at fewer
# samples than SPPS' first; "" for none), REF_SPP (1024), THREADS (2), OUT (out/race), SAMPLERS
# ("sobol random": Mirage's [render] sampler values raced by single/multiple; "default" sets
# none), MIRAGE (build/mirage: another build to race, e.g. an older one against the same
# references), PHOTON_PASSES ("2 8 24": pass counts of the photon rows; "" for none), PHOTONS
# (100000: photons per pass), PASS_SPP (4: samples per pixel per pass), TIME_LIMITS (seconds of
# the timed rows: the scene's race.times, else "0.03 0.1 0.3 1 3"; "" for none), CHECK_SPP
# (64), MEAN_SECONDS (10), MIRAGE_SHARED_DATA.
# Installs Blender when missing (pipeline/install-deps.sh). Prints one table per race
# (also its CSV) and the equal-error time ratios.
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${MIRAGE_SHARED_DATA:-../shared/data}
CYCLES_PY="$(realpath -m "$DATA/../tools/cycles_vdb.py")"
REGIMES="sun sky-white sky-hdr lamp-point lamp-spot lamp-sphere fire haze"
MODE=${1:-single}
case " single multiple both all check $REGIMES " in
  *" $MODE "*) ;;
  *) echo "race: expected single, multiple, both, all, check or a regime: $REGIMES" >&2; exit 1 ;;
esac
SPPS=${SPPS:-4 16 64}
LOW_SPPS=${LOW_SPPS-1 2}
REF_SPP=${REF_SPP:-1024}
THREADS=${THREADS:-2}
OUT=${OUT:-out/race}
SAMPLERS=${SAMPLERS:-sobol random}
PHOTON_PASSES=${PHOTON_PASSES-2 8 24}
PHOTONS=${PHOTONS:-100000}
PASS_SPP=${PASS_SPP:-4}
CHECK_SPP=${CHECK_SPP:-64}
MEAN_SECONDS=${MEAN_SECONDS:-10}
MIRAGE=${MIRAGE:-build/mirage}
TIME_LIMITS_GIVEN=${TIME_LIMITS+yes}
TIME_LIMITS_USER=${TIME_LIMITS-}
no_data() { echo "race: $1 not found: the race needs the reference data folder" >&2; exit 1; }
if [ "$MODE" = check ] && [ ! -f "$CYCLES_PY" -o ! -d "$DATA/vdb" ]; then
  echo "race: check skipped: no reference data folder ($DATA)"
  exit 77  # ctest's SKIP_RETURN_CODE
fi
[ -f "$CYCLES_PY" ] || no_data "$CYCLES_PY"
[ "$MODE" = check ] || command -v blender >/dev/null || pipeline/install-deps.sh >/dev/null
[ -x "$MIRAGE" ] || pipeline/build.sh build >/dev/null
mkdir -p "$OUT"

# --- The scene of a race: its `# race.*` lines and the inputs the suite makes itself ---------

meta() {  # scene key → the values of its `# race.<key> = …` lines, joined by spaces
  sed -n "s/^# race\.$2 = //p" "$1" | paste -sd' '
}

# Inputs that are not in ../shared/data: made once into OUT/inputs with the Mirage raced (the
# procedural caches) and pipeline/sky_hdr.py, and found there by name.
made_input() {  # name → its path, made when missing
  local dir="$OUT/inputs" path="$OUT/inputs/$1"
  mkdir -p "$dir"
  if [ ! -s "$path" ]; then
    case "$1" in
      fog_sphere.vdb) "$MIRAGE" make-asset fog-sphere -o "$path" >/dev/null ;;
      fire_flames.vdb)
        # The fire of assets/scenes/fire_smoke.toml, its kelvin grid kept only where the
        # flame grid is active (race_fire.toml says why): the stack after reading holds vel,
        # temperature, flame, density (ages 0-3); -clip replaces temperature by
        # clip_temperature at age 0 and moves the rest down one.
        "$MIRAGE" make-asset fire -o "$dir/fire.vdb" --resolution 96 --seed 3 >/dev/null
        vdb_tool -quiet -read "$dir/fire.vdb" -clip vdb=1 mask=2 -write vdb=0,2,3 "$path" >/dev/null
        ;;
      sky.mirage.hdr) python3 pipeline/sky_hdr.py mirage "$path" >/dev/null ;;
      sky.cycles.hdr) python3 pipeline/sky_hdr.py cycles "$path" >/dev/null ;;
      *) echo "race: no input named $1 in $DATA/vdb or among the made ones" >&2; exit 1 ;;
    esac
  fi
  echo "$path"
}

input_path() {  # name → ../shared/data/vdb/<name> if there, else the made input
  if [ -f "$DATA/vdb/$1" ]; then realpath "$DATA/vdb/$1"; else realpath "$(made_input "$1")"; fi
}

# An argument naming an input (a whole word, or the part after '=') becomes its path.
resolve_args() {  # words… → one per line
  local w
  for w in "$@"; do
    case "$w" in
      *=*.vdb | *=*.hdr) echo "${w%%=*}=$(input_path "${w#*=}")" ;;
      *.vdb | *.hdr) echo "$(input_path "$w")" ;;
      *) echo "$w" ;;
    esac
  done
}

# Sets the globals every render below reads: SCENE, VDB, NAME (the outputs' stem), RES_X/RES_Y,
# CYCLES_ARGS (cycles_vdb.py's medium and lights), MIRAGE_SETS (--set of the volume file and
# any race.set); load_camera then sets CAMERA (Mirage's --set of Cycles' camera).
load_scene() {  # scene.toml name [cache.vdb]
  SCENE=$1
  NAME=$2
  VDB=$(realpath -m "${3:-$(input_path "$(meta "$SCENE" cache)")}")
  [ -f "$VDB" ] || no_data "$VDB"
  local wh
  wh=$(sed -n 's/^resolution *= *\[ *\([0-9]*\) *, *\([0-9]*\) *\].*/\1 \2/p' "$SCENE" | head -1)
  RES_X=${wh% *}
  RES_Y=${wh#* }
  mapfile -t CYCLES_ARGS < <(resolve_args $(meta "$SCENE" cycles))
  MIRAGE_SETS=(--set "volume.0.file=$VDB")
  local kv
  while read -r kv; do
    [ -n "$kv" ] && MIRAGE_SETS+=(--set "$kv")
  done < <(resolve_args $(meta "$SCENE" set))
  # The timed rows' limits: TIME_LIMITS when given (even empty), else the scene's race.times.
  TIME_LIMITS=$TIME_LIMITS_USER
  [ -n "$TIME_LIMITS_GIVEN" ] || TIME_LIMITS=$(meta "$SCENE" times)
}

# The camera Cycles frames the cache with at this resolution (cycles_vdb.py's CYCLES_VDB line
# of a 1-spp probe, kept in OUT), as Mirage's --set arguments.
load_camera() {
  local file="$OUT/$NAME.camera"
  if [ ! -s "$file" ]; then
    blender -b --factory-startup --python-exit-code 1 --python "$CYCLES_PY" -- "$VDB" \
      "$OUT/$NAME.probe.exr" "$RES_X" "$RES_Y" 1 --density-scale 5 --threads "$THREADS" 2>&1 |
      python3 -c '
import re, sys
for line in sys.stdin:
    m = re.search(r"camera_pos \(([^)]*)\) look_at \(([^)]*)\) .* fov_deg ([0-9.]+)", line)
    if m:
        print("camera.position=[%s]" % m.group(1).replace(" ", ""))
        print("camera.look_at=[%s]" % m.group(2).replace(" ", ""))
        print("camera.fov=%s" % m.group(3))
' >"$file"
    rm -f "$OUT/$NAME.probe.exr"
    [ -s "$file" ] || { echo "race: no camera from cycles_vdb.py for $VDB" >&2; exit 1; }
  fi
  CAMERA=()
  local kv
  while read -r kv; do CAMERA+=(--set "$kv"); done <"$file"
}

# --- Renders -------------------------------------------------------------------------------

# References take another seed (7): with a low-discrepancy sampler, their first samples would
# otherwise be the very samples of the images they judge.
# Cycles: prints its render seconds (scene set-up excluded).
cycles() {  # bounces spp exr [seed]
  blender -b --factory-startup --python-exit-code 1 --python "$CYCLES_PY" -- "$VDB" "$3" \
    "$RES_X" "$RES_Y" "$2" "${CYCLES_ARGS[@]}" --volume-bounces "$1" --threads "$THREADS" \
    --pixel-filter box --seed "${4:-0}" 2>&1 |
    awk '/RENDER_SECONDS/ {print $2}'
}

# Mirage with a named integrator: prints its frame seconds (mirage:frame_seconds: the
# integrator's set-up, such as single scattering's light guide, and the render; loading and
# writing excluded).
mirage() {  # integrator sampler spp exr [seed]
  local sampler=()
  [ "$2" = default ] || sampler=(--set "render.sampler=$2")
  "$MIRAGE" render "$SCENE" "${MIRAGE_SETS[@]}" "${CAMERA[@]}" \
    --set "render.integrator=$1" "${sampler[@]}" --spp "$3" --threads "$THREADS" \
    --seed "${5:-0}" -o "$4" --quiet >/dev/null
  oiiotool --info -v "$4" | awk -F'"' '/mirage:frame_seconds/ {print $2}'
}

# Mirage's progressive photon mapper in P passes: prints the seconds since the frame began
# (mirage:time_spent: integrator set-up and every pass's photon map included).
photon() {  # passes exr
  "$MIRAGE" render "$SCENE" "${MIRAGE_SETS[@]}" "${CAMERA[@]}" \
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
  "$MIRAGE" render "$SCENE" "${MIRAGE_SETS[@]}" "${CAMERA[@]}" \
    --set render.integrator=auto "$@" --threads "$THREADS" -o "$exr" --quiet >/dev/null
  oiiotool --info -v "$exr" |
    awk -F'"' '/mirage:time_spent/ {t = $2} /mirage:frame_seconds/ {f = $2} END {print (t != "" ? t : f)}'
}

# --- The race ------------------------------------------------------------------------------

# One race: the references, then per spp Cycles and Mirage's sample rows, then the timed and
# photon rows; its table, OUT's CSV and the equal-error ratios. Row kinds: sampler:<name>
# (the reference integrator with that sampler), default (the default given --spp N), volpath,
# single (by samples), timed (the default given --time-limit), photon (progressive passes).
race() {  # tag bounces integrator title rows...
  local tag=$1 bounces=$2 integrator=$3 title=$4
  shift 4
  local rows=("$@") kind spp limit passes
  printf '\n%s\n' "$title"
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
  # Mirage's default below Cycles' cheapest count too (LOW_SPPS): where its cheapest render
  # is already below the error Cycles reaches at its own, the time is read off a curve rather
  # than bounded by that render.
  if [[ " ${rows[*]} " == *" default "* ]]; then
    for spp in $LOW_SPPS; do
      row "mirage default" "$spp" "$(default_render "$tag.default.exr" --spp "$spp" --seed 0)" \
        "$tag.default.exr" "$tag.mirage_ref.exr"
    done
  fi
  for spp in $SPPS; do
    row cycles "$spp" "$(cycles "$bounces" "$spp" "$tag.cycles.exr")" "$tag.cycles.exr" \
      "$tag.cycles_ref.exr"
    for kind in "${rows[@]}"; do
      case "$kind" in
        sampler:*)
          row "mirage ${kind#sampler:}" "$spp" \
            "$(mirage "$integrator" "${kind#sampler:}" "$spp" "$tag.mirage.exr")" \
            "$tag.mirage.exr" "$tag.mirage_ref.exr" ;;
        default)
          row "mirage default" "$spp" "$(default_render "$tag.default.exr" --spp "$spp" --seed 0)" \
            "$tag.default.exr" "$tag.mirage_ref.exr" ;;
        volpath | single)
          row "mirage $kind" "$spp" "$(mirage "$kind" default "$spp" "$tag.$kind.exr")" \
            "$tag.$kind.exr" "$tag.mirage_ref.exr" ;;
      esac
    done
  done
  for kind in "${rows[@]}"; do
    case "$kind" in
      timed)
        for limit in $TIME_LIMITS; do
          row "mirage timed" "$limit" \
            "$(default_render "$tag.timed.exr" --time-limit "$limit" --seed 0)" \
            "$tag.timed.exr" "$tag.mirage_ref.exr"
        done ;;
      photon)
        for passes in $PHOTON_PASSES; do
          row "mirage photon" "$((passes * PASS_SPP))" "$(photon "$passes" "$tag.photon.exr")" \
            "$tag.photon.exr" "$tag.mirage_ref.exr"
        done ;;
    esac
  done
  # Equal error: each Mirage's time to Cycles' relMSE at each spp (pipeline/race_ratio.py).
  python3 pipeline/race_ratio.py "$tag.csv"
}

# The race on smoke1 (or CACHE) of the single / multiple modes.
legacy_race() {  # single | volpath
  local samplers=() s
  for s in $SAMPLERS; do samplers+=("sampler:$s"); done
  local cache=${CACHE:-$DATA/vdb/smoke1.vdb}
  load_scene tests/bench/smoke1_race.toml "$(basename "$cache" .vdb)" "$cache"
  load_camera
  local title
  title=$(printf '%s.vdb %sx%s, %d threads: Cycles --volume-bounces %d against mirage --integrator %s' \
    "$NAME" "$RES_X" "$RES_Y" "$THREADS" "$([ "$1" = single ] && echo 0 || echo 64)" "$1")
  if [ "$1" = single ]; then
    race "$OUT/$NAME.single" 0 single "$title" "${samplers[@]}"
  else
    race "$OUT/$NAME.volpath" 64 volpath "$title" "${samplers[@]}" default timed photon
  fi
}

# --- The regime suite ----------------------------------------------------------------------

scene_of() {  # regime → its scene file
  case "$1" in
    sun) echo tests/bench/smoke1_race.toml ;;
    *) echo "tests/bench/race_${1//-/_}.toml" ;;
  esac
}

# What the machine was doing: the before-and-after lines of OUT/<regime>.run.txt.
run_note() {  # when
  printf '%s %s: %s, %s threads, load average %s, mirage %s\n' "$1" \
    "$(date -u '+%Y-%m-%d %H:%M UTC')" "$(lscpu | sed -n 's/^Model name: *//p' | head -1)" "$THREADS" \
    "$(cut -d' ' -f1-3 /proc/loadavg)" "$MIRAGE"
}

# Cycles' mean at the regime's bounces and at 4× (64 samples, seed 3; at a quarter where 4×
# would pass Blender's limit of 1024, as the same agreement then says the quarter already had
# it all), and the Mirage reference's cut paths: both compute essentially all of the light when
# the means agree within 1 % and no path was cut. Kept in OUT/<regime>.bounces.txt.
bounce_check() {  # tag bounces
  local file="$1.bounces.txt" b other=$(($2 * 4))
  [ -s "$file" ] && { cat "$file"; return; }
  [ "$other" -le 1024 ] || other=$(($2 / 4))
  for b in "$2" "$other"; do
    cycles "$b" 64 "$1.bounces.exr" 3 >/dev/null
    printf 'cycles %s bounces, 64 spp: mean RGB %s\n' "$b" \
      "$(oiiotool --stats "$1.bounces.exr" | sed -n 's/.*Stats Avg: *\([^ ]* [^ ]* [^ ]*\).*/\1/p')"
  done >"$file"
  rm -f "$1.bounces.exr"
  printf 'mirage reference: mirage:capped_paths %s (max_depth %s)\n' \
    "$(oiiotool --info -v "$1.mirage_ref.exr" | awk -F'"' '/mirage:capped_paths/ {print $2}')" \
    "$(sed -n 's/^max_depth *= *\([0-9]*\).*/\1/p' "$SCENE" | grep . || echo 10000)" >>"$file"
  cat "$file"
}

# The checks of a light inside a medium, where a reference of 1024 samples may hold fireflies
# and relMSE against it hides them: the noise between seeds 1 and 2 at CHECK_SPP (relMSE of one
# against the other, halved: each image's own), Mirage's default against Cycles; and the mean
# of a MEAN_SECONDS default render against the volpath reference's.
checks() {  # tag bounces
  local tag=$1 t1 t2 c1 c2 m
  {
    t1=$(cycles "$2" "$CHECK_SPP" "$tag.seed1.exr" 1)
    t2=$(cycles "$2" "$CHECK_SPP" "$tag.seed2.exr" 2)
    c1=$(python3 pipeline/relmse.py "$tag.seed1.exr" "$tag.seed2.exr")
    printf 'seeds cycles %s spp: relMSE between seeds / 2 = %.4g (%s s, %s s)\n' "$CHECK_SPP" \
      "$(echo "$c1" | awk '{print $1 / 2}')" "$t1" "$t2"
    t1=$(default_render "$tag.seed1.exr" --spp "$CHECK_SPP" --seed 1)
    t2=$(default_render "$tag.seed2.exr" --spp "$CHECK_SPP" --seed 2)
    c2=$(python3 pipeline/relmse.py "$tag.seed1.exr" "$tag.seed2.exr")
    printf 'seeds mirage default %s spp: relMSE between seeds / 2 = %.4g (%s s, %s s); %s\n' \
      "$CHECK_SPP" "$(echo "$c2" | awk '{print $1 / 2}')" "$t1" "$t2" \
      "$(awk -v a="$c2" -v b="$c1" 'BEGIN {printf "mirage / cycles %.2f", a / b}')"
    t1=$(default_render "$tag.mean.exr" --time-limit "$MEAN_SECONDS" --seed 1)
    m=$(python3 pipeline/race_summary.py --mean "$tag.mean.exr" "$tag.mirage_ref.exr")
    printf 'mean mirage default --time-limit %s (%s s) against the %s-sample volpath: %s\n' \
      "$MEAN_SECONDS" "$t1" "$REF_SPP" "$m"
  } | tee "$tag.checks.txt"
  rm -f "$tag.seed1.exr" "$tag.seed2.exr" "$tag.mean.exr"
}

# A reference as the PNG the suite's pictures are judged by, exposed for the medium (its
# median covered pixel reads 0.18; flames and lamps clip), sRGB.
preview() {  # exr png
  oiiotool "$1" --ch R,G,B --mulc "$(python3 pipeline/race_summary.py --exposure "$1")" \
    --colorconvert linear srgb -o "$2"
}

regime() {  # regime
  local tag="$OUT/$1" rows=(default timed) r
  load_scene "$(scene_of "$1")" "$1"
  load_camera
  for r in $(meta "$SCENE" rows); do rows+=("$r"); done
  local bounces
  bounces=$(meta "$SCENE" bounces)
  run_note start >"$tag.run.txt"
  local title
  title=$(printf 'regime %s: %s %sx%s, %d threads: Cycles --volume-bounces %d against mirage' \
    "$1" "$(basename "$VDB")" "$RES_X" "$RES_Y" "$THREADS" "$bounces")
  race "$tag" "$bounces" volpath "$title (reference volpath)" "${rows[@]}"
  bounce_check "$tag" "$bounces"
  case " $(meta "$SCENE" checks) " in *" seeds "*) checks "$tag" "$bounces" ;; esac
  run_note end >>"$tag.run.txt"
  for r in cycles mirage; do preview "$tag.${r}_ref.exr" "$tag.${r}_ref.png"; done
  python3 pipeline/race_plot.py "$tag.csv" "$tag.png" "$1"
}

# A regime's scene without racing (ctest RaceSuite.EveryRegimeSceneLoads): its `# race.*`
# lines and Cycles' options against the scene Mirage renders (pipeline/race_scene_check.py), its
# made inputs made, and `mirage info` on it with the race's --set, whose choice of integrator
# and of sampled colour it prints.
check_regime() {  # regime
  load_scene "$(scene_of "$1")" "$1"
  local key meta_args=() info
  for key in cache cycles bounces rows checks times set; do
    meta_args+=("$key=$(meta "$SCENE" "$key")")
  done
  python3 pipeline/race_scene_check.py "$SCENE" "$CYCLES_PY" "${meta_args[@]}" -- \
    "${CYCLES_ARGS[@]}"
  info=$("$MIRAGE" info "$SCENE" "${MIRAGE_SETS[@]}") ||
    { echo "race: $1: mirage info $SCENE failed" >&2; exit 1; }
  printf '  %s\n' "$(grep -o 'integrator: auto: .*' <<<"$info")" \
    "$(grep -o 'sampled colour .*' <<<"$info" | tr -s ' ')"
}

case "$MODE" in
  check) for r in $REGIMES; do check_regime "$r"; done && echo "race check: ok" ;;
  single) legacy_race single ;;
  multiple) legacy_race volpath ;;
  both) legacy_race single && legacy_race volpath ;;
  all) for r in $REGIMES; do regime "$r"; done ;;
  *) regime "$MODE" ;;
esac
