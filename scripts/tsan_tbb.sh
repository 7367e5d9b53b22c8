#!/usr/bin/env bash
# Prints the folder of a oneTBB built with ThreadSanitizer, building it first if it is not cached.
#
# ThreadSanitizer sees only the synchronisation of code it instrumented: against Debian's libtbb
# every hand-over of work between TBB's threads (its task queues and work stealing) looks like a
# race on whatever the task touches. So the thread-sanitizer tests run on the same oneTBB release as
# the installed libtbb-dev (same headers, same soname), built from Debian's own source package with
# oneTBB's TBB_SANITIZE=thread. Nothing of it goes into the repository; the build is cached under
# ~/.cache/meshrepair (about 3 minutes on 2 cores the first time).
set -euo pipefail

version=$(dpkg-query -W -f '${Version}' libtbb-dev) # e.g. 2021.8.0-2+deb12u1
upstream=${version%%-*}
cache="${XDG_CACHE_HOME:-$HOME/.cache}/meshrepair/onetbb-tsan-$upstream"
if [ -f "$cache/lib/libtbb.so.12" ]; then
  echo "$cache"
  exit 0
fi

mirror="${DEBIAN_MIRROR:-http://deb.debian.org/debian}"
suite=$(. /etc/os-release && echo "$VERSION_CODENAME")
tarball="onetbb_$upstream.orig.tar.xz"
work=$(mktemp -d)
trap 'rm -rf "$work" "$cache.partial"' EXIT

# The expected checksum comes from the suite's index of source packages (a truncated or altered
# download fails here, not in the middle of a build).
sha256=$(curl -fsS "$mirror/dists/$suite/main/source/Sources.xz" | xz -dc |
  awk -v file="$tarball" '/^Package: /{ours = ($2 == "onetbb")}
    ours && $3 == file && length($1) == 64 && !sha {sha = $1} END {print sha}')
[ -n "$sha256" ] || { echo "tsan_tbb: $tarball is not in $mirror ($suite)" >&2; exit 2; }
curl -fsS -o "$work/$tarball" "$mirror/pool/main/o/onetbb/$tarball"
echo "$sha256  $work/$tarball" | sha256sum --check --quiet

mkdir "$work/src"
tar -xJf "$work/$tarball" -C "$work/src" --strip-components=1
# TBB_STRICT=OFF: GCC warns that TSan ignores atomic_thread_fence, and oneTBB's strict mode makes
# that warning an error. tbbmalloc stays out: the tests use the system allocator.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$work/src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DTBB_SANITIZE=thread -DTBB_STRICT=OFF -DTBB_TEST=OFF -DTBBMALLOC_BUILD=OFF -DTBB_EXAMPLES=OFF \
  -DCMAKE_INSTALL_PREFIX="$cache.partial" "${launcher[@]}" >"$work/configure.log" ||
  { cat "$work/configure.log" >&2; exit 1; }
cmake --build "$work/build" --parallel "$(nproc)" >"$work/build.log" || { tail -50 "$work/build.log" >&2; exit 1; }
cmake --install "$work/build" >/dev/null
mkdir -p "$(dirname "$cache")"
mv "$cache.partial" "$cache"
echo "$cache"
