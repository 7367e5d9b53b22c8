#!/bin/sh
# Runs simplify_bench on the largest corpus models and a generated 1M-face
# torus, one process per model. Usage: bench/simplify_bench.sh BUILD_DIR [CORPUS_DIR]
set -eu
build=${1:?build directory}
corpus=${2:-/work/shared/corpus}
for model in "$corpus/derived/ogre_subdiv_highres.ply" "$corpus/c3d/igea.ply" \
             "$corpus/trimesh/counter.unitsmm.STL" "$corpus/thingi10k/99865.stl" gen-torus:1000000; do
  "$build/bench/simplify_bench" "$model"
done
