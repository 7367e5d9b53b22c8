#!/bin/sh
# Runs simplify_bench on the largest corpus models and a generated 1M-face
# torus, one process per model, then (when meshlabserver and xvfb-run are
# installed) MeshLab's quadric edge collapse to the same face count, measured
# with mesh-check against the same input. One JSON line per model and tool.
# Usage: bench/simplify_bench.sh BUILD_DIR [CORPUS_DIR]
set -eu
build=${1:?build directory}
corpus=${2:-/work/shared/corpus}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

meshlab_quadric() {  # INPUT FACES MODEL_NAME: one JSON line
  sed "s/TARGET_FACES/$2/" "$(dirname "$0")/meshlab_quadric.mlx" > "$work/quadric.mlx"
  /usr/bin/time -f "%e %M" -o "$work/time.txt" \
    xvfb-run -a meshlabserver -i "$1" -o "$work/meshlab.ply" -s "$work/quadric.mlx" > "$work/meshlab.log" 2>&1
  # Exit 1 means "farther than epsilon": the numbers are what we want.
  "$build/tools/mesh-check/mesh-check" "$work/meshlab.ply" --reference "$1" --expect none \
    --no-self-intersections --json "$work/check.json" > /dev/null || [ $? -eq 1 ]
  python3 - "$work/check.json" "$work/time.txt" "$3" <<'EOF'
import json, sys
check = json.load(open(sys.argv[1]))
seconds, kb = open(sys.argv[2]).read().split()
d = check["distance"]
print(json.dumps({"model": sys.argv[3], "tool": "meshlab_quadric", "faces_after": check["surface"]["faces"],
                  "seconds": float(seconds), "peak_rss_mb": int(kb) / 1024,
                  "distance_max": d["to_reference_max"], "distance_back_max": d["from_reference_max"]}))
EOF
}

for model in "$corpus/derived/ogre_subdiv_highres.ply" "$corpus/c3d/igea.ply" \
             "$corpus/trimesh/counter.unitsmm.STL" "$corpus/thingi10k/99865.stl" gen-torus:1000000; do
  "$build/bench/simplify_bench" "$model" --write-input "$work/input.ply" | tee "$work/ours.json"
  if command -v meshlabserver > /dev/null && command -v xvfb-run > /dev/null; then
    faces=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["faces_after"])' "$work/ours.json")
    meshlab_quadric "$work/input.ply" "$faces" "$model"
  fi
done
