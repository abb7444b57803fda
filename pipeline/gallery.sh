#!/usr/bin/env bash
# The gallery: renders every shipped scene (assets/scenes/*.toml) at a quality preset and lays
# the pictures out on one contact sheet.
#
#   pipeline/gallery.sh [--quality preview|final] [--only NAME,NAME…] [--docs] [--reuse]
#
# Writes out/gallery/NAME.png (through the scene's OCIO display/view) and NAME.exr, the contact
# sheet out/gallery/gallery.png with each picture's name, preset and render time under it, and
# out/gallery/times.csv (scene, preset, resolution, seconds). The preview preset renders each
# scene at half its stated resolution (a few minutes for the whole set on 2 cores); final at
# its full resolution with 4× its samples (docs/performance.md, "Quality presets").
# --docs also writes the sheet, reduced, to docs/gallery.png (the README's first picture).
# --reuse keeps a picture already rendered at this preset since the scene and the binary last
# changed (its time is the one recorded then).
# The procedural caches the scenes read are made first with `mirage make-asset` (the scenes'
# header comments name them); smoke1_sun.toml needs ../shared/data and is skipped without it.
# Environment: MIRAGE (default build/mirage; built when missing), MIRAGE_THREADS (default: all).
set -euo pipefail
cd "$(dirname "$0")/.."

quality=preview
only=""
docs=0
reuse=0
while [ $# -gt 0 ]; do
    case "$1" in
        --quality) quality=${2:?--quality needs preview or final}; shift 2 ;;
        --only) only=${2:?--only needs scene names}; shift 2 ;;
        --docs) docs=1; shift ;;
        --reuse) reuse=1; shift ;;
        -h|--help) sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "gallery.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
done
case "$quality" in
    preview) scale=2 ;;
    final) scale=1 ;;
    *) echo "gallery.sh: --quality must be preview or final, not '$quality'" >&2; exit 2 ;;
esac

MIRAGE=${MIRAGE:-build/mirage}
[ -x "$MIRAGE" ] || pipeline/build.sh build
threads=()
[ -n "${MIRAGE_THREADS:-}" ] && threads=(--threads "$MIRAGE_THREADS")
out=out/gallery
mkdir -p "$out/tiles"

# The caches, each made once (assets/scenes/*.vdb are not in git).
asset() {  # kind file [make-asset options…]
    local kind=$1 file=assets/scenes/$2
    shift 2
    [ -f "$file" ] || "$MIRAGE" make-asset "$kind" -o "$file" "$@" >/dev/null
}
asset fog-sphere fog_sphere.vdb
asset fire fire_smoke.vdb --resolution 96 --seed 3
asset fire fire_haze.vdb --resolution 64 --seed 3
asset ocean ocean_plume.vdb
asset plume demo_plume.vdb --resolution 256 --seed 7
asset smoke-sphere smoke_sphere.vdb --resolution 96 --seed 7

# The [film] resolution a scene states, divided by the preset's scale.
resolution() {
    local wh
    wh=$(sed -n 's/^resolution *= *\[ *\([0-9]*\) *, *\([0-9]*\) *\].*/\1 \2/p' "$1" | head -1)
    set -- $wh
    echo "$(( ($1 + scale - 1) / scale ))x$(( ($2 + scale - 1) / scale ))"
}

# The captions' font (oiiotool --text needs one it can open; fonts-dejavu-core).
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
[ -f "$font" ] || font=$(find /usr/share/fonts -name '*.ttf' 2>/dev/null | head -1)
[ -n "$font" ] || { echo "gallery.sh: no TrueType font for the captions (fonts-dejavu-core)" >&2; exit 1; }

csv=$out/times.csv
echo "scene,preset,resolution,seconds" > "$csv"
tiles=()
for scene in assets/scenes/*.toml; do
    name=$(basename "$scene" .toml)
    if [ -n "$only" ] && [[ ",$only," != *",$name,"* ]]; then continue; fi
    if grep -q 'shared/data' "$scene" && [ ! -d ../shared/data ]; then
        echo "gallery: $name skipped (needs ../shared/data)" >&2
        continue
    fi
    res=$(resolution "$scene")
    stamp=$out/$name.$quality.seconds  # --reuse: a render newer than the scene and the binary
    if [ "$reuse" = 1 ] && [ -f "$stamp" ] && [ "$stamp" -nt "$scene" ] && [ "$stamp" -nt "$MIRAGE" ]; then
        seconds=$(cat "$stamp")
        echo "gallery: $name reused ($seconds s)" >&2
    else
        echo "gallery: $name ($quality, $res)" >&2
        t0=$(date +%s.%N)
        "$MIRAGE" render "$scene" --quality "$quality" --resolution "$res" -q "${threads[@]}" \
            -o "$out/$name.exr" --preview "$out/$name.png"
        t1=$(date +%s.%N)
        seconds=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
        echo "$seconds" > "$stamp"
    fi
    echo "$name,$quality,$res,$seconds" >> "$csv"
    # A tile: the picture fitted into 320×240 on black, its caption in the strip below. (The
    # caption is drawn on an image of its own: oiiotool 2.4 aborts drawing text on a read one;
    # --paste puts the image below the top of the stack onto the top one.)
    oiiotool --create 320x32 3 \
        --text:x=8:y=22:size=15:color=0.9,0.9,0.9:font="$font" "$name | $quality | ${seconds} s" \
        "$out/$name.png" --ch R,G,B --fit:pad=1 320x240 --create 320x272 3 --paste +0+0 \
        --paste +0+240 -o "$out/tiles/$name.png"
    tiles+=("$out/tiles/$name.png")
done
[ ${#tiles[@]} -gt 0 ] || { echo "gallery.sh: no scene rendered" >&2; exit 1; }

# The sheet: four tiles a row.
cols=4
rows=$(( (${#tiles[@]} + cols - 1) / cols ))
oiiotool "${tiles[@]}" --mosaic:pad=4 "${cols}x${rows}" -o "$out/gallery.png"
echo "gallery: $out/gallery.png, times in $csv" >&2
if [ "$docs" = 1 ]; then
    oiiotool "$out/gallery.png" --resize 50% -d uint8 -o docs/gallery.png
    echo "gallery: docs/gallery.png ($(du -k docs/gallery.png | cut -f1) KB)" >&2
fi
