#!/usr/bin/env bash
# Fuzzes the scene parser, the VDB loading path and the light files Mirage parses itself (IES
# profiles, RGBE sky maps) with libFuzzer: builds the targets with clang
# (ASan + UBSan, -DMIRAGE_FUZZ=ON, in build-fuzz/) and runs each for FUZZ_SECONDS. Exits non-zero
# if a target finds a crash, a sanitizer error, a leak, a timeout or an out-of-memory, and keeps
# the input that caused it in out/fuzz/findings/. New interesting inputs go to out/fuzz/corpus/;
# FUZZ_MERGE=1 merges those that add coverage into tests/fuzz/corpus/ (the corpus in the
# repository, which ctest replays with the normal build: tests/unit/fuzz_corpus_test.cpp).
# Environment: FUZZ_SECONDS (default 60 per target), FUZZ_TARGETS (default "scene vdb lights"),
# FUZZ_RSS_MB (default 2048), MIRAGE_JOBS (build jobs, default: cores). FUZZ_RUNS=N with
# FUZZ_SEED=S (default 1) runs N inputs from seed S instead of a time: the same inputs on every
# machine, so a CI run is reproducible here (.ci/run uses it for the scene target).
set -euo pipefail
cd "$(dirname "$0")/.."
pipeline/install-deps.sh fuzz

SECONDS_PER_TARGET=${FUZZ_SECONDS:-60}
TARGETS=${FUZZ_TARGETS:-"scene vdb lights"}
RSS_MB=${FUZZ_RSS_MB:-2048}
BUILD_DIR=build-fuzz
OUT=out/fuzz
LAUNCHER=()
if command -v ccache >/dev/null; then
  LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}  # paths under the checkout hashed relative: a worktree hits
fi

CC=clang CXX=clang++ cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "${LAUNCHER[@]}" -DMIRAGE_FUZZ=ON -DMIRAGE_BUILD_BENCH=OFF >/dev/null
# shellcheck disable=SC2086
ninja -C "$BUILD_DIR" -j "${MIRAGE_JOBS:-$(nproc)}" $(for t in $TARGETS; do echo "fuzz_$t"; done)

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tests/fuzz/lsan.supp}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export ASAN_SYMBOLIZER_PATH=${ASAN_SYMBOLIZER_PATH:-$(command -v llvm-symbolizer || true)}
status=0
for t in $TARGETS; do
  mkdir -p "$OUT/corpus/$t" "$OUT/findings"
  if [ -n "${FUZZ_RUNS:-}" ]; then
    budget=(-runs="$FUZZ_RUNS" -seed="${FUZZ_SEED:-1}")
  else
    budget=(-max_total_time="$SECONDS_PER_TARGET")
  fi
  args=("${budget[@]}" -timeout=30 -rss_limit_mb="$RSS_MB"
        -malloc_limit_mb="$RSS_MB" -print_final_stats=1
        -artifact_prefix="$OUT/findings/$t-")
  # Scene files are text: the dictionary of TOML syntax and Mirage's keys speeds the search.
  if [ "$t" = scene ]; then args+=(-dict=tests/fuzz/scene.dict -max_len=4096); fi
  # Light files: small profiles and pictures reach every branch of both parsers.
  if [ "$t" = lights ]; then args+=(-max_len=2048); fi
  # OpenVDB allocates the compressed size a corrupt leaf claims (terabytes) and ASan's operator
  # new aborts where a normal build throws std::bad_alloc, which Mirage reports as one message.
  # Fork mode with -ignore_ooms keeps fuzzing past those; each is still saved in findings/ and
  # listed below (FUZZ_IGNORE_OOMS=0 makes them fail the run).
  if [ "$t" = vdb ]; then
    args+=(-max_len=16384)
    if [ "${FUZZ_IGNORE_OOMS:-1}" = 1 ]; then args+=(-fork=1 -ignore_ooms=1); fi
  fi
  log="$OUT/fuzz_$t.log"
  echo "fuzz: $t for ${FUZZ_RUNS:-$SECONDS_PER_TARGET s} ${FUZZ_RUNS:+inputs from seed ${FUZZ_SEED:-1}} (log: $log)"
  # The first corpus folder receives new inputs; the repository's seeds are only read.
  # A counted run starts from the repository's corpus alone, so it is the same run everywhere.
  grow="$OUT/corpus/$t"
  if [ -n "${FUZZ_RUNS:-}" ]; then grow=$(mktemp -d); fi
  if "$BUILD_DIR/tests/fuzz/fuzz_$t" "${args[@]}" "$grow" "tests/fuzz/corpus/$t" \
       >"$log" 2>&1; then
    grep -E "stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)|^#[0-9]+: cov" "$log" | tail -4 || true
    if ls "$OUT/findings/$t-"* >/dev/null 2>&1; then
      echo "fuzz: $t: ignored out-of-memory inputs (third-party; docs/hostile-input.md):"
      ls "$OUT/findings/$t-"*
    fi
  else
    status=1
    echo "fuzz: $t FOUND A PROBLEM; input kept in $OUT/findings/ (tail of $log):" >&2
    # An uncaught exception aborts with only "deadly signal" from libFuzzer: its what() and the
    # stack's frames in Mirage say where.
    grep -E "ERROR|SUMMARY|runtime error|Test unit written|terminate called|what\(\)| in mirage::" \
      "$log" | head -30 >&2 || true
  fi
  if [ "${FUZZ_MERGE:-0}" = 1 ]; then
    "$BUILD_DIR/tests/fuzz/fuzz_$t" -merge=1 -rss_limit_mb="$RSS_MB" -malloc_limit_mb="$RSS_MB" \
      "tests/fuzz/corpus/$t" "$OUT/corpus/$t" >>"$log" 2>&1 || true
  fi
done
exit $status
