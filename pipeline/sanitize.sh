#!/usr/bin/env bash
# Sanitizer runs (clang 14; README, "Hostile input and sanitizers"):
#   asan  ASan + UBSan (-fno-sanitize-recover=undefined: any undefined behaviour fails the test)
#         on the unit tests (ctest -L unit). It shares build-fuzz/ with pipeline/fuzz.sh: the
#         library is compiled once, with the sanitizers and libFuzzer's coverage hooks, for both.
#   tsan  ThreadSanitizer (build-tsan/) on the tests that run the parallel photon pass, the
#         parallel photon-map build and the tiled render on several threads.
# Usage: pipeline/sanitize.sh [asan|tsan|all] (default all). Prints each stage's build and test
# time. Environment: MIRAGE_JOBS (build jobs, default: cores), CTEST_JOBS (default: cores).
set -euo pipefail
cd "$(dirname "$0")/.."
STAGE=${1:-all}
pipeline/install-deps.sh fuzz
JOBS=${MIRAGE_JOBS:-$(nproc)}
CTEST_JOBS=${CTEST_JOBS:-$(nproc)}
LAUNCHER=()
if command -v ccache >/dev/null; then LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
export ASAN_SYMBOLIZER_PATH=${ASAN_SYMBOLIZER_PATH:-$(command -v llvm-symbolizer || true)}
# The tests exercising threads: same result on 1 and 2 threads (photon pass, photon map), the
# tiled renderer's callbacks and resume, and the renders of the photon integrator.
TSAN_TESTS=${TSAN_TESTS:-"PhotonPass|PhotonMap|Renderer|PhotonIntegrator|VolumeEstimate"}

configure() {  # build-dir, extra cmake args…
  local dir=$1
  shift
  CC=clang CXX=clang++ cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "${LAUNCHER[@]}" -DMIRAGE_BUILD_TESTS=ON -DMIRAGE_BUILD_BENCH=OFF "$@" >/dev/null
}

timed() {  # label, command…
  local label=$1 start
  shift
  start=$(date +%s)
  "$@"
  echo "sanitize: $label took $(($(date +%s) - start)) s"
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
  configure build-tsan -DMIRAGE_TSAN=ON
  timed "tsan build" ninja -C build-tsan -j "$JOBS" mirage_unit_tests
  export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1}
  timed "tsan tests" ctest --test-dir build-tsan -R "$TSAN_TESTS" -j 1 --timeout 900 \
    --output-on-failure || status=1
fi
exit $status
