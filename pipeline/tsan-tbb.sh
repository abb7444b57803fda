#!/usr/bin/env bash
# Builds oneTBB's libtbb.so.12 with ThreadSanitizer, for pipeline/sanitize.sh tsan.
#
# Why: TSan sees happens-before only where the code doing the synchronising is instrumented.
# Debian's libtbb.so is not, and the synchronisation of a parallel_for lives in it (a task
# pushed to a deque by r1::spawn and stolen by another thread, task memory recycled by TBB's
# small-object pool, the caller woken when the last task ends) while the task objects are
# written and read by TBB's header templates compiled into Mirage's own, instrumented code.
# Uninstrumented, TSan reports races between TBB's headers on both sides that no annotation in
# Mirage's calls can order (docs/hostile-input.md, "Hostile input and sanitizers").
#
# The source is Debian's own package of exactly the installed libtbb12 version (so that the
# library matches the headers Mirage is compiled against), fetched with apt-get source from the
# archives the system already uses, through a private apt state in <dir>/apt: the system's apt
# configuration is read, never changed. Only libtbb is built (Mirage and OpenVDB link nothing
# else of oneTBB). Prints the directory holding libtbb.so.12 on its last line; a second run
# with the same version reuses the library.
# Usage: pipeline/tsan-tbb.sh <dir>   (sanitize.sh uses build-tsan/onetbb)
# Environment: MIRAGE_JOBS (build jobs, default: cores).
set -euo pipefail
DIR=$(mkdir -p "$1" && cd "$1" && pwd)
JOBS=${MIRAGE_JOBS:-$(nproc)}
VERSION=$(dpkg-query -W -f='${Version}' libtbb12)
HEADERS=$(dpkg-query -W -f='${Version}' libtbb-dev)
if [ "$HEADERS" != "$VERSION" ]; then
  echo "tsan-tbb: libtbb-dev $HEADERS and libtbb12 $VERSION differ; the library built must match" \
    "the headers Mirage compiles against" >&2
  exit 1
fi
LIB="$DIR/lib"
if [ -f "$LIB/libtbb.so.12" ] && [ "$(cat "$DIR/version" 2>/dev/null)" = "$VERSION" ]; then
  echo "$LIB"
  exit 0
fi
rm -rf "$DIR/apt" "$DIR/src" "$DIR/build" "$LIB" "$DIR/version"

# deb-src entries for the archives the system installs from (deb822 .sources and one-line
# .list files alike), in a private apt state.
APT="$DIR/apt"
mkdir -p "$APT/sources" "$APT/lists/partial" "$APT/cache/archives/partial"
for f in /etc/apt/sources.list.d/*.sources; do
  [ -f "$f" ] && sed -e 's/^Types:.*/Types: deb-src/' "$f" >"$APT/sources/$(basename "$f")"
done
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
  [ -f "$f" ] && sed -n -e 's/^deb /deb-src /p' "$f" >"$APT/sources/$(basename "$f")"
done
APT_OPTS=(-o Dir::Etc::SourceList=/dev/null -o "Dir::Etc::SourceParts=$APT/sources"
  -o "Dir::State::Lists=$APT/lists" -o "Dir::Cache=$APT/cache" -o APT::Sandbox::User=root)
# An archive without sources (a vendor's repository) fails its own index only; apt-get source
# below says clearly if Debian's is unreachable too.
apt-get "${APT_OPTS[@]}" -qq update || echo "tsan-tbb: some source indexes failed to load" >&2
mkdir -p "$DIR/src"
(cd "$DIR/src" && apt-get "${APT_OPTS[@]}" -qq source --download-only "onetbb=$VERSION" &&
  dpkg-source --no-check -x ./*.dsc onetbb >/dev/null)

# RelWithDebInfo, as build-tsan: TSan's reports name TBB's frames with file and line. No
# interprocedural optimisation (clang's needs the LLVM linker plugin) and no -Werror (TBB's
# own warnings under clang 14 are not Mirage's to fix).
LAUNCHER=()
if command -v ccache >/dev/null; then LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
CC=clang CXX=clang++ cmake -S "$DIR/src/onetbb" -B "$DIR/build" -G Ninja \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "${LAUNCHER[@]}" -DTBB_SANITIZE=thread -DTBB_TEST=OFF \
  -DTBBMALLOC_BUILD=OFF -DTBB_STRICT=OFF -DTBB_ENABLE_IPO=OFF -DTBB_EXAMPLES=OFF >/dev/null
ninja -C "$DIR/build" -j "$JOBS" tbb >/dev/null
mkdir -p "$LIB"
built=$(find "$DIR/build" -name 'libtbb.so.12.*' -type f | head -1)
[ -n "$built" ] || { echo "tsan-tbb: no libtbb.so.12.* under $DIR/build" >&2; exit 1; }
cp "$built" "$LIB/"
ln -sf "$(basename "$built")" "$LIB/libtbb.so.12"
echo "$VERSION" >"$DIR/version"
echo "$LIB"
