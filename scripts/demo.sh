#!/usr/bin/env bash
# The main job on a bundled example: install, build, then convert the broken
# example box (binary STL) to GLB. (meshrepair will take this place.)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
mkdir -p out
build/tools/format-convert/format-convert examples/models/box_with_hole.stl out/box_with_hole.glb
echo "wrote out/box_with_hole.glb"
