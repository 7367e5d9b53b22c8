#!/usr/bin/env bash
# The unit and in-process tool tests (mr_tests) under AddressSanitizer and
# UndefinedBehaviorSanitizer, in build-asan/. Any report fails the run.
# Then the sanitizer build's tools must write the same bytes as the Release
# build's (build/, from scripts/test.sh), with 1 and 2 threads.
# Extra arguments go to ctest (e.g. -R hole to run a subset).
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
# This build has debug info (-g), for which ccache would key on the folder; a fresh clone elsewhere
# should still hit the cache (its objects then name another folder in their debug info).
export CCACHE_NOHASHDIR=1
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# OpenVDB leaks the nodes of a grid whose reading throws (upstream; see the file).
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp"

# Warnings are errors in the Release build (scripts/test.sh); with sanitizers GCC 12 also warns
# falsely inside OpenMesh and libstdc++ (-Wmaybe-uninitialized), so they stay warnings here.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMR_SANITIZE=address \
  -DMR_BUILD_BENCH=OFF -DMR_WITH_PYTHON=OFF -DMR_WERROR=OFF -DMR_TEST_SPEC="~[slow]" >/dev/null
cmake --build build-asan --parallel "$(nproc)" --target mr_tests meshrepair tetrahedralize
# mr_tests but its [slow] end-to-end cases (over 12 s each here, 90% of the time; the Release
# suite runs them); the Python-driven tests (module, batch, Makefile, kills) run on Release only.
ctest --test-dir build-asan --parallel "$(nproc)" --output-on-failure \
  -E "^(bench_runner|python_module|meshrepair_batch|examples_makefile|fault_killed_runs)$" "$@"
[ -x build/tools/meshrepair/meshrepair ] || { echo "sanitize: build/ has no Release tools; run scripts/test.sh first" >&2; exit 2; }
tests/determinism/compare_builds.sh build build-asan
