#!/usr/bin/env bash
# Sanitizer runs (clang 14; docs/hostile-input.md, "Hostile input and sanitizers"):
#   asan  ASan + UBSan (-fno-sanitize-recover=undefined: any undefined behaviour fails the test)
#         on the unit tests (ctest -L unit). It shares build-fuzz/ with pipeline/fuzz.sh: the
#         library is compiled once, with the sanitizers and libFuzzer's coverage hooks, for both.
#   tsan  ThreadSanitizer (build-tsan/) on the tests that run the parallel photon pass, the
#         parallel photon-map build and the tiled render on several threads, against a libtbb
#         built with TSan (pipeline/tsan-tbb.sh: TSan cannot see the synchronisation inside
#         Debian's uninstrumented one). A gate: any report fails it, and so does a deliberate
#         race (tests/tsan/race_canary.cpp) that TSan does not report.
# Usage: pipeline/sanitize.sh [asan|tsan|all] (default all). Prints each stage's build and test
# time. Environment: MIRAGE_JOBS (build jobs, default: cores), CTEST_JOBS (default: cores).
set -euo pipefail
cd "$(dirname "$0")/.."
STAGE=${1:-all}
pipeline/install-deps.sh fuzz
JOBS=${MIRAGE_JOBS:-$(nproc)}
CTEST_JOBS=${CTEST_JOBS:-$(nproc)}
LAUNCHER=()
if command -v ccache >/dev/null; then
  LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}  # paths under the checkout hashed relative: a worktree hits
fi
export ASAN_SYMBOLIZER_PATH=${ASAN_SYMBOLIZER_PATH:-$(command -v llvm-symbolizer || true)}
# The tests exercising threads: same result on 1 and 2 threads (photon pass, photon map), the
# tiled renderer's callbacks and resume, the volume estimate, the parallel leaf read and the
# parallel majorant splat, the next frame's load beside a render — suites of the program
# mirage_thread_tests (tests/CMakeLists.txt),
# the only test sources compiled under TSan. TSAN_TESTS='\.' with TSAN_PROGRAM=mirage_unit_tests
# runs the whole unit suite under TSan instead.
TSAN_TESTS=${TSAN_TESTS:-"PhotonPass|PhotonMap|Renderer|VolumeEstimate|ParallelLoad|Majorant|FramePrefetch"}
TSAN_PROGRAM=${TSAN_PROGRAM:-mirage_thread_tests}
TSAN_LABEL=threads
if [ "$TSAN_PROGRAM" = mirage_unit_tests ]; then TSAN_LABEL=unit; fi

configure() {  # build-dir, extra cmake args…
  local dir=$1
  shift
  CC=clang CXX=clang++ cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "${LAUNCHER[@]}" -DMIRAGE_BUILD_TESTS=ON -DMIRAGE_BUILD_BENCH=OFF "$@" >/dev/null
}

timed() {  # label, command… — returns the command's status (called as `timed … || status=1`,
  # where `set -e` is off inside the function: without the explicit return a failing command
  # was reported by its echo's status, 0)
  local label=$1 start rc=0
  shift
  start=$(date +%s)
  "$@" || rc=$?
  echo "sanitize: $label took $(($(date +%s) - start)) s"
  return $rc
}

status=0
if [ "$STAGE" = asan ] || [ "$STAGE" = all ]; then
  configure build-fuzz -DMIRAGE_FUZZ=ON
  timed "asan build" ninja -C build-fuzz -j "$JOBS" mirage_unit_tests
  export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
  timed "asan tests" ctest --test-dir build-fuzz -L unit -j "$CTEST_JOBS" --timeout 900 \
    --output-on-failure || status=1
fi
if [ "$STAGE" = tsan ] || [ "$STAGE" = all ]; then
  start=$(date +%s)
  TSAN_TBB=$(pipeline/tsan-tbb.sh build-tsan/onetbb | tail -1)
  echo "sanitize: tsan oneTBB took $(($(date +%s) - start)) s"
  configure build-tsan -DMIRAGE_TSAN=ON -DMIRAGE_TSAN_TBB_DIR="$TSAN_TBB"
  timed "tsan build" ninja -C build-tsan -j "$JOBS" "$TSAN_PROGRAM" race_canary
  # The run means something only if the tests (and the mirage they start) load that libtbb.
  for bin in build-tsan/mirage "build-tsan/tests/$TSAN_PROGRAM" build-tsan/tests/race_canary; do
    if ! grep -q "libtbb.so.12 => $TSAN_TBB/" <<<"$(ldd "$bin")"; then
      echo "sanitize: $bin does not load the TSan-built libtbb from $TSAN_TBB" >&2
      exit 1
    fi
  done
  # Reports go to files (log_path), so that one in a mirage process started by a test fails
  # the gate even where that test only expected a non-zero exit. tsan.supp: third-party
  # libraries' own threads, each entry justified there.
  REPORTS=$PWD/build-tsan/tsan-reports
  rm -rf "$REPORTS"
  mkdir -p "$REPORTS"
  TSAN_BASE="${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1}"
  TSAN_BASE+=":suppressions=$PWD/tests/tsan/tsan.supp"
  canary=0
  TSAN_OPTIONS="$TSAN_BASE:log_path=$REPORTS/canary" build-tsan/tests/race_canary || canary=$?
  if [ "$canary" -ne 0 ] && [ "$canary" -ne 3 ] &&
    grep -qs "WARNING: ThreadSanitizer: data race" "$REPORTS"/canary.* &&
    grep -qs "racyTally" "$REPORTS"/canary.*; then
    echo "sanitize: the race canary was reported, as it must be (exit $canary)"
    rm -f "$REPORTS"/canary.*
  else
    echo "sanitize: ThreadSanitizer did not report the race canary (exit $canary): the gate" \
      "is blind; see $REPORTS" >&2
    status=1
  fi
  export TSAN_OPTIONS="$TSAN_BASE:log_path=$REPORTS/report"
  timed "tsan tests" ctest --test-dir build-tsan -L "$TSAN_LABEL" -R "$TSAN_TESTS" -j 1 --timeout 900 \
    --output-on-failure || status=1
  if compgen -G "$REPORTS/report.*" >/dev/null; then
    echo "sanitize: ThreadSanitizer reports ($REPORTS):"
    cat "$REPORTS"/report.*
    status=1
  else
    echo "sanitize: tsan clean: no ThreadSanitizer report"
  fi
fi
exit $status
