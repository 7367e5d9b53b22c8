#!/usr/bin/env bash
# The same input gives the same bytes from two builds (e.g. Release and the
# sanitizer build) and from 1 and 2 threads: meshrepair to GLB and STL,
# tetrahedralize to MSH, on the bundled example models.
#   tests/determinism/compare_builds.sh BUILD_A BUILD_B
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 BUILD_A BUILD_B" >&2; exit 2; }
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() {  # build tool input output threads
  "$1/tools/$2/$2" "$3" "$4" -q -j "$5"
}

failures=0
compared=0
for model in "$root"/examples/models/*; do
  name=$(basename "${model%.*}")
  for job in "meshrepair glb" "meshrepair stl" "tetrahedralize msh"; do
    read -r tool ext <<<"$job"
    reference="$work/$name.$tool.a1.$ext"
    run "$1" "$tool" "$model" "$reference" 1
    for variant in "$1 2" "$2 1" "$2 2"; do
      read -r build threads <<<"$variant"
      out="$work/$name.$tool.$(basename "$build").$threads.$ext"
      run "$build" "$tool" "$model" "$out" "$threads"
      compared=$((compared + 1))
      if ! cmp -s "$reference" "$out"; then
        echo "differs: $tool $(basename "$model") -> .$ext, $build -j $threads against $1 -j 1" >&2
        failures=$((failures + 1))
      fi
    done
  done
done
echo "determinism: $compared outputs compared, $failures differ"
[ "$failures" -eq 0 ]
