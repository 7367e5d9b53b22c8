#!/usr/bin/env bash
# The main job on a bundled example: install, build, then repair the broken
# example box (binary STL: a missing face, a duplicated face, non-manifold
# edges) into a watertight GLB.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
mkdir -p out
build/tools/meshrepair/meshrepair examples/models/box_with_hole.stl out/box_with_hole.glb --stats out/box_with_hole.json
echo "wrote out/box_with_hole.glb"
