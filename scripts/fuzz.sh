#!/usr/bin/env bash
# Fuzzes the readers and the meshrepair pipeline with libFuzzer (fuzz/).
#
#   scripts/fuzz.sh SECONDS [TARGET...]
#
# Configures and builds build-fuzz/ (clang, -DMR_FUZZ=ON: ASan + UBSan) when
# needed, seeds each target's corpus from the examples, tests/data and the
# examples written in every format by our own format-convert and
# tetrahedralize, then runs each target for SECONDS (one at a time, one core,
# libFuzzer's fork mode so that a crash does not end the run) and prints
# executions per second, coverage (cov/ft) and crashes. Crash, leak, timeout
# and out-of-memory inputs are kept in build-fuzz/crashes/TARGET/, logs in
# build-fuzz/logs/, the growing corpora in build-fuzz/corpus/TARGET/.
# Without TARGETs, all of them (build-fuzz/fuzz/targets.txt).
#
# A crash fixed gets its input, minimized (fuzz_TARGET -minimize_crash=1
# -runs=10000 FILE), under tests/data/fuzz/TARGET/; mr_tests replays those
# ([fuzz]). Environment: MR_BUILD_LOCK=FILE runs configure and build under
# flock FILE; MR_FUZZ_JOBS (default: all cores) build jobs; MR_FORMAT_CONVERT
# and MR_TETRAHEDRALIZE: the tools that make the seeds (default: build-fuzz's);
# MR_FUZZ_SKIP_BUILD=1: run the targets as they are built.
set -euo pipefail

usage() {
  echo "usage: scripts/fuzz.sh SECONDS [TARGET...]" >&2
  exit 2
}
[[ $# -ge 1 && $1 =~ ^[0-9]+$ ]] || usage
seconds=$1
shift

root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-fuzz
jobs=${MR_FUZZ_JOBS:-$(nproc)}

locked() {
  if [[ -n ${MR_BUILD_LOCK:-} ]]; then flock "$MR_BUILD_LOCK" "$@"; else "$@"; fi
}

if [[ ! -f $build/build.ninja ]]; then
  locked env CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DMR_FUZZ=ON \
    -DMR_BUILD_TESTS=OFF -DMR_BUILD_BENCH=OFF -DMR_WITH_PYTHON=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
if [[ $# -gt 0 ]]; then
  targets=("$@")
else
  mapfile -t targets <"$build/fuzz/targets.txt"
fi
seeds=$build/seeds
# The seeds are made by our own tools: these, or the instrumented build's.
convert=${MR_FORMAT_CONVERT:-$build/tools/format-convert/format-convert}
tetrahedralize=${MR_TETRAHEDRALIZE:-$build/tools/tetrahedralize/tetrahedralize}
build_targets=()
if [[ ! -f $seeds/.done ]]; then
  [[ -n ${MR_FORMAT_CONVERT:-} ]] || build_targets+=(format-convert)
  [[ -n ${MR_TETRAHEDRALIZE:-} ]] || build_targets+=(tetrahedralize)
fi
for t in "${targets[@]}"; do build_targets+=("fuzz_$t"); done
[[ -n ${MR_FUZZ_SKIP_BUILD:-} ]] || locked cmake --build "$build" --parallel "$jobs" --target "${build_targets[@]}"

# The largest input libFuzzer makes, per target: small enough for fast runs,
# large enough for a few dozen elements.
max_len() {
  case $1 in
    stl_binary | obj | off | ply_ascii | ply_binary | drc) echo 4096 ;;
    meshrepair) echo 2048 ;;
    vdb) echo 100000 ;;
    *) echo 8192 ;;
  esac
}

# Seeds: sources, every surface format of each, and tet meshes of the small ones.
make_seeds() {
  local gen=$seeds/generated
  rm -rf "$seeds"
  mkdir -p "$gen"
  # Tiny models of our own: a tetrahedron, and one with a face missing.
  printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' >"$gen/tet.obj"
  printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\nf 1/1/1 3/1/1 2/1/1\nf 1 2 4\nf 1 4 3\n' \
    >"$gen/open_tet.obj"
  local sources=("$root"/examples/models/*.stl "$root"/examples/models/*.obj "$root"/examples/models/*.ply
    "$root"/tests/data/*.obj "$gen/tet.obj" "$gen/open_tet.obj")
  local src name
  for src in "${sources[@]}"; do
    name=$(basename "${src%.*}")
    # Quiet, and keep going: a seed that cannot be made is only a missing seed.
    "$convert" "$src" "$gen/$name.bin.stl" -q || true
    "$convert" "$src" "$gen/$name.ascii.stl" --ascii -q || true
    "$convert" "$src" "$gen/$name.obj" -q 2>/dev/null || true
    "$convert" "$src" "$gen/$name.off" -q || true
    "$convert" "$src" "$gen/$name.bin.ply" -q || true
    "$convert" "$src" "$gen/$name.ascii.ply" --ascii -q || true
    "$convert" "$src" "$gen/$name.gltf" -q || true
    "$convert" "$src" "$gen/$name.glb" -q || true
    "$convert" "$src" "$gen/$name.draco.gltf" --draco -q || true
    "$convert" "$src" "$gen/$name.draco.glb" --draco -q || true
    "$convert" "$src" "$gen/$name.drc" -q || true
  done
  # Level sets a few voxels across (a VDB file is a few kB per 8^3 leaf).
  "$convert" "$gen/tet.obj" "$gen/tet.vdb" --voxel-size 0.25 -q || true
  "$convert" "$gen/tet.obj" "$gen/tet_empty.vdb" --voxel-size 0.5 --half-width 1 -q || true
  "$convert" "$root/examples/models/overlapping_boxes.obj" "$gen/boxes.vdb" --voxel-size 1 --half-width 1 -q || true
  for src in "$gen/tet.obj" "$root/examples/models/box_with_hole.stl"; do
    name=$(basename "${src%.*}")
    # A handful of tets: no lattice, long edges, no improvement.
    "$tetrahedralize" "$src" "$gen/$name.41.bin.msh" -l 1 --lattice 0 --max-passes 0 -j 1 -q || continue
    "$convert" "$gen/$name.41.bin.msh" "$gen/$name.41.ascii.msh" --ascii -q || true
    "$convert" "$gen/$name.41.bin.msh" "$gen/$name.22.bin.msh" --msh-version 2.2 -q || true
    "$convert" "$gen/$name.41.bin.msh" "$gen/$name.22.ascii.msh" --msh-version 2.2 --ascii -q || true
    "$convert" "$gen/$name.41.bin.msh" "$gen/$name.mesh" -q || true
  done
  local t pattern
  for t in stl_binary stl_ascii obj off ply_ascii ply_binary gltf glb drc msh medit vdb meshrepair; do
    case $t in
      stl_binary) pattern='*.bin.stl' ;;
      stl_ascii) pattern='*.ascii.stl' ;;
      ply_ascii) pattern='*.ascii.ply' ;;
      ply_binary) pattern='*.bin.ply' ;;
      medit) pattern='*.mesh' ;;
      meshrepair) pattern='*.obj' ;;
      *) pattern="*.$t" ;;
    esac
    mkdir -p "$seeds/$t"
    find "$gen" -name "$pattern" -exec cp {} "$seeds/$t/" \;
  done
  cp "$root"/examples/models/*.stl "$root"/examples/models/*.obj "$seeds/stl_ascii/" 2>/dev/null || true
  cp "$root"/examples/models/*.obj "$root"/tests/data/*.obj "$seeds/obj/"
  cp "$root"/examples/models/*.ply "$seeds/ply_binary/"
  find "$seeds/meshrepair" -type f -size +2k -delete
  find "$gen" -name "*.stl" -size -2k -exec cp {} "$seeds/meshrepair/" \;
  touch "$seeds/.done"
}
[[ -f $seeds/.done ]] || make_seeds

mkdir -p "$build/logs" "$build/crashes" "$build/corpus"
printf '%-11s %7s %9s %7s %7s %8s  %s\n' target seconds exec/s cov ft crashes log
for t in "${targets[@]}"; do
  corpus=$build/corpus/$t
  crashes=$build/crashes/$t
  log=$build/logs/$t.log
  mkdir -p "$corpus" "$crashes" "$build/work/$t"
  # Regression inputs seed the corpus too: fixed bugs stay covered.
  inputs=("$seeds/$t")
  [[ -d $root/tests/data/fuzz/$t ]] && inputs+=("$root/tests/data/fuzz/$t")
  before=$(find "$crashes" -type f | wc -l)
  start=$(date +%s)
  # From the target's own directory: a glTF's external buffers resolve there.
  (cd "$build/work/$t" &&
    TMPDIR=$(test -d /dev/shm && echo /dev/shm || echo /tmp) MR_FUZZ_SLOW_DIR=$build/slow/$t \
      LSAN_OPTIONS=suppressions=$root/fuzz/lsan.supp \
      "$build/fuzz/fuzz_$t" "$corpus" "${inputs[@]}" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 \
      -ignore_ooms=1 -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="$(max_len "$t")" \
      -artifact_prefix="$crashes/" -print_final_stats=1 -print_funcs=0) >"$log" 2>&1 || true
  elapsed=$(($(date +%s) - start))
  # Fork mode's status lines: "#N: cov: C ft: F corp: K exec/s E oom/timeout/crash: a/b/c time: Ts ..."
  status=$(grep -E '^#[0-9]+: cov: ' "$log" | tail -n 1 || true)
  field() { sed -nE "s|.* $1:? ([0-9]+).*|\\1|p" <<<"$status"; }
  found=$(($(find "$crashes" -type f | wc -l) - before))
  slow=""
  [[ -d $build/slow/$t ]] && slow=" ($(find "$build/slow/$t" -type f | wc -l) inputs over 1 s in build-fuzz/slow/$t)"
  printf '%-11s %7s %9s %7s %7s %8s  %s%s\n' "$t" "$elapsed" "$(field exec/s)" "$(field cov)" "$(field ft)" \
    "$found" "${log#"$root"/}" "$slow"
done
