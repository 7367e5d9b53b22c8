#!/usr/bin/env bash
# Installs everything the build, the tests and the benchmarks need on Debian 12,
# then the project-local npm tools (the Khronos glTF validator). Idempotent:
# a second run only checks. Runs apt-get through sudo when not root.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  # toolchain
  build-essential cmake ninja-build ccache pkg-config git
  # libraries
  libopenmesh-dev libopenvdb-dev libblosc-dev libboost-dev libboost-iostreams-dev libcgal-dev libgmp-dev libeigen3-dev
  libdraco-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libtbb-dev catch2 libbenchmark-dev
  # command-line peers and checkers used by tests and benchmarks
  draco gmsh tetgen admesh time util-linux python3 python3-numpy python3-meshio python3-matplotlib
  # the Python module, the batch tool on Dask, and their tests
  pybind11-dev python3-dev python3-pytest python3-distributed python3-dask
  # formatting, fuzzing and sanitizer runtimes
  clang-format clang libfuzzer-14-dev libclang-rt-14-dev
  # the ThreadSanitizer build of oneTBB from Debian's source package (scripts/tsan_tbb.sh)
  curl xz-utils ca-certificates
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node.js runs the glTF validator; keep an existing installation (e.g. nodesource).
command -v node >/dev/null 2>&1 || missing+=(nodejs)
command -v npm >/dev/null 2>&1 || missing+=(npm)

if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [ ! -d tests/tools/node_modules/gltf-validator ]; then
  echo "setup: installing the glTF validator (npm)" >&2
  npm ci --prefix tests/tools --no-audit --no-fund --loglevel=error >/dev/null
fi
