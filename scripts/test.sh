#!/usr/bin/env bash
# The test command: install dependencies, build, run every test with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh -DMR_WERROR=ON
ctest --test-dir build --parallel "$(nproc)" --output-on-failure
