#!/usr/bin/env bash
# Production-sized caches (issue 38): makes `mirage make-asset pyro` caches of SIZES active
# density voxels (half-float density and temperature, vel at twice the voxel size) in DIR, then
# times the first image of each — `mirage render tests/bench/bigcache.toml --spp 1`, the whole
# command, under /usr/bin/time -v — and prints a Markdown table: voxels, file size, wall and
# CPU seconds, peak resident memory, and the load average at the start (the machine may be
# shared: CPU seconds are the robust figure). With CYCLES=1 and Blender installed, Blender
# Cycles renders the same density through ../shared/tools/cycles_vdb.py at the same size.
# Settings by environment: SIZES ("1e7 1e8 1e9"), DIR (/tmp/mirage-bigcache; caches are kept
# there and remade only when missing), MIRAGE (build/mirage), RUNS (1), KEEP (0: delete caches
# of 10^9 voxels or more at the end), CYCLES (0).
set -euo pipefail
cd "$(dirname "$0")/.."
SIZES=${SIZES:-1e7 1e8 1e9}
DIR=${DIR:-/tmp/mirage-bigcache}
MIRAGE=${MIRAGE:-build/mirage}
RUNS=${RUNS:-1}
KEEP=${KEEP:-0}
CYCLES=${CYCLES:-0}
mkdir -p "$DIR"
[ -x "$MIRAGE" ] || pipeline/build.sh build >/dev/null

# "<wall s> <cpu s> <peak GiB>" of a command, from GNU time's verbose report.
measure() {
  local log="$DIR/time.log"
  /usr/bin/time -v "$@" >/dev/null 2>"$log" || { tail -5 "$log" >&2; return 1; }
  awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); w = 0;
                for (i = 1; i <= n; ++i) w = w * 60 + t[i]}
              /User time/ {c += $2} /System time/ {c += $2}
              /Maximum resident set size/ {m = $2 / 1048576}
              END {printf "%.1f %.1f %.2f\n", w, c, m}' "$log"
}
loadavg() { cut -d' ' -f1-3 /proc/loadavg; }

printf '| density voxels | file | renderer | wall s | CPU s | peak GiB | load avg |\n'
printf '|---|---|---|---|---|---|---|\n'
for size in $SIZES; do
  cache="$DIR/pyro_$size.vdb"
  [ -f "$cache" ] || "$MIRAGE" make-asset pyro --voxels "$size" -o "$cache" --quiet >/dev/null
  bytes=$(stat -c %s "$cache")
  file=$(awk -v b="$bytes" 'BEGIN {printf "%.1f MB", b / 1e6}')
  voxels=$size
  for run in $(seq "$RUNS"); do
    load=$(loadavg)
    read -r wall cpu peak < <(measure "$MIRAGE" render tests/bench/bigcache.toml \
      --set "volume.0.file=$cache" --spp 1 -o "$DIR/mirage_$size.exr" --quiet)
    printf '| %s | %s | Mirage | %s | %s | %s | %s |\n' "$voxels" "$file" "$wall" "$cpu" \
      "$peak" "$load"
    if [ "$CYCLES" = 1 ] && command -v blender >/dev/null; then
      load=$(loadavg)
      if result=$(measure blender -b --factory-startup --python-exit-code 1 --python \
          ../shared/tools/cycles_vdb.py -- "$cache" "$DIR/cycles_$size.exr" 640 360 1 \
          --density-scale 20 --albedo 0.9 --grid density --sun-dir=-0.5,-0.6,-0.4 \
          --sun-strength 1000 --camera-distance 4.2); then
        read -r wall cpu peak <<< "$result"
        printf '| %s | %s | Cycles | %s | %s | %s | %s |\n' "$voxels" "$file" "$wall" "$cpu" \
          "$peak" "$load"
      else
        printf '| %s | %s | Cycles | failed | | | %s |\n' "$voxels" "$file" "$load"
      fi
    fi
  done
  case "$size" in 1e9|1e10) [ "$KEEP" = 1 ] || rm -f "$cache" ;; esac
done
