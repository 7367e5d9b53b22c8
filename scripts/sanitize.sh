#!/usr/bin/env bash
# The unit and in-process tool tests (mr_tests) under a sanitizer; any report fails the run.
#
#   scripts/sanitize.sh address [ctest args]   AddressSanitizer + UndefinedBehaviorSanitizer, in
#       build-asan/: every case but the [slow] ones; then the sanitizer build's tools must write
#       the same bytes as the Release build's (build/, from scripts/test.sh), with 1 and 2 threads.
#   scripts/sanitize.sh thread [ctest args]    ThreadSanitizer, in build-tsan/: the cases of the
#       multithreaded stages (predicates, winding numbers, filter, insertion, improvement,
#       simplification, repair, hole filling, checks), against a oneTBB built with ThreadSanitizer
#       (scripts/tsan_tbb.sh); first a deliberate race must be reported.
#
# Extra arguments go to ctest (e.g. -R hole to run a subset).
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-}"
case "$mode" in
  address | thread) shift ;;
  *) echo "usage: scripts/sanitize.sh address|thread [ctest args]" >&2; exit 2 ;;
esac
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
# These builds have debug info (-g), for which ccache would key on the folder; a fresh clone
# elsewhere should still hit the cache (its objects then name another folder in their debug info).
export CCACHE_NOHASHDIR=1
# The Python-driven tests (module, batch, Makefile, kills) run on the Release build only.
python_driven="^(bench_runner|python_module|meshrepair_batch|examples_makefile|fault_killed_runs)$"

configure() { # folder sanitizer test-spec
  # Warnings are errors in the Release build (scripts/test.sh); with sanitizers GCC 12 also warns
  # falsely inside OpenMesh and libstdc++ (-Wmaybe-uninitialized), so they stay warnings here.
  # -g1 (line tables only) is all a sanitizer report needs, and compiles the CGAL-heavy files in
  # two thirds of the time of full debug info.
  cmake -S . -B "$1" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMR_SANITIZE="$2" \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
    -DMR_BUILD_BENCH=OFF -DMR_WITH_PYTHON=OFF -DMR_WERROR=OFF -DMR_TEST_SPEC="$3" >/dev/null
}

run_address() {
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  # OpenVDB leaks the nodes of a grid whose reading throws (upstream; see the file).
  export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp"
  # mr_tests but its [slow] end-to-end cases (over 12 s each here, 90% of the time; the Release
  # suite runs them).
  configure build-asan address "~[slow]"
  cmake --build build-asan --parallel "$(nproc)" --target mr_tests meshrepair tetrahedralize
  ctest --test-dir build-asan --parallel "$(nproc)" --output-on-failure -E "$python_driven" "$@"
  [ -x build/tools/meshrepair/meshrepair ] || { echo "sanitize: build/ has no Release tools; run scripts/test.sh first" >&2; exit 2; }
  tests/determinism/compare_builds.sh build build-asan
}

run_thread() {
  local tbb
  tbb=$(scripts/tsan_tbb.sh)
  export LD_LIBRARY_PATH="$tbb/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/tests/tsan.supp"
  # The stages that run on several threads, but the [slow] cases (the Release suite runs them), the
  # tests that start gmsh or Python (programs that cannot load the instrumented libtbb) and OpenVDB
  # (which uses TBB from its own uninstrumented library).
  local spec="" tag
  for tag in kernel aabb envelope winding tetmesh improve tetrahedralize sizing simplify repair keep \
    hole_fill check e2e; do
    spec+="${spec:+,}[$tag]~[slow]~[gmsh]~[vdb]"
  done
  configure build-tsan thread "$spec"
  cmake --build build-tsan --parallel "$(nproc)" --target mr_tests
  local canary
  canary=$(build-tsan/tests/mr_tests "[tsan-canary]" 2>&1 || true)
  grep -q "ThreadSanitizer: data race" <<<"$canary" ||
    { echo "sanitize: ThreadSanitizer did not report the deliberate race:" >&2; echo "$canary" >&2; exit 1; }
  ctest --test-dir build-tsan --parallel "$(nproc)" --output-on-failure -E "$python_driven" "$@"
}

"run_$mode" "$@"
