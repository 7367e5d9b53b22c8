#!/usr/bin/env bash
# I/O benchmark: our readers and writers on a 1M-triangle mesh, OpenMesh's
# STL reader and meshio's in the same run. Run after scripts/build.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-/tmp/mr_io_bench}
build/bench/io_bench "$dir" "${2:-1000000}"
# Debian's python3 has python3-meshio; a pyenv python3 earlier on PATH may not.
/usr/bin/python3 - "$dir/mesh.stl" <<'PY'
import sys, time, os
import meshio
start = time.perf_counter()
mesh = meshio.read(sys.argv[1])
s = time.perf_counter() - start
faces = sum(len(c.data) for c in mesh.cells)
mb = os.path.getsize(sys.argv[1]) / 1e6
print("| %-34s | %8.3f | %8.1f | %9.1f | %10d |" % ("read binary STL (meshio, python)", s, mb, mb / s, faces))
PY
