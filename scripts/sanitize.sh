#!/usr/bin/env bash
# The unit and in-process tool tests under sanitizers, each in its own build folder:
#   scripts/sanitize.sh            AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/)
#   scripts/sanitize.sh thread     ThreadSanitizer on the multithreaded stages (build-tsan/)
# Any report fails the run. Extra arguments after the mode go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
mode="${1:-address}"
shift || true

case "$mode" in
  address)
    folder=build-asan
    sanitizer=address
    export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
    export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
    # Every test of mr_tests; the Python-driven tests (module, batch, Makefile, kills) run the Release build.
    selection=(-E "^(bench_runner|python_module|meshrepair_batch|examples_makefile|fault_killed_runs)$")
    ;;
  thread)
    folder=build-tsan
    sanitizer=thread
    export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan.supp"
    # The stages that run on several threads: predicates, winding numbers, the filter, improvement, hole fill.
    selection=(-R "thread|determinis|winding|filter|improv|predicate|parallel|hole-fill writes")
    ;;
  *)
    echo "usage: scripts/sanitize.sh [address|thread] [ctest options]" >&2
    exit 2
    ;;
esac

# Warnings are errors in the Release build (scripts/test.sh); with sanitizers GCC 12 also warns
# falsely inside OpenMesh and libstdc++ (-Wmaybe-uninitialized), so they stay warnings here.
cmake -S . -B "$folder" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMR_SANITIZE="$sanitizer" \
  -DMR_BUILD_BENCH=OFF -DMR_WITH_PYTHON=OFF -DMR_WERROR=OFF >/dev/null
cmake --build "$folder" --parallel "$(nproc)" --target mr_tests
ctest --test-dir "$folder" --parallel "$(nproc)" --output-on-failure "${selection[@]}" "$@"
