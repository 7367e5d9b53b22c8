#!/usr/bin/python3
"""A sizing field for `tetrahedralize --sizing`: a background tet mesh over a model's box whose node
values (MSH $NodeData "values", fTetWild's --bg-mesh convention) are a target edge length, FINE
within RADIUS of a point and growing linearly to COARSE at twice that distance.

Lengths and the radius are relative to the model's bounding-box diagonal, as tetrahedralize's -l;
the point defaults to the box centre. The background is N^3 cubes, each split into six tets, over the
box enlarged by 10% on each side. Written as MSH 2.2 ASCII (gmsh, meshio and fTetWild read it).

    bench/make_sizing_field.py MODEL --out field.msh --fine 0.01 --coarse 0.05 --radius 0.2
    tetrahedralize MODEL out.msh --sizing field.msh
"""
import argparse
import itertools
import os
import subprocess
import sys
import tempfile


def model_box(model, build_dir):
    """The bounding box of MODEL's vertices, read through our format-convert (any format -> OBJ)."""
    convert = os.path.join(build_dir, "tools", "format-convert", "format-convert")
    with tempfile.TemporaryDirectory() as tmp:
        obj = os.path.join(tmp, "model.obj")
        subprocess.run([convert, model, obj], check=True, stdout=subprocess.DEVNULL)
        lo, hi = [float("inf")] * 3, [float("-inf")] * 3
        with open(obj) as f:
            for line in f:
                if line.startswith("v "):
                    p = [float(x) for x in line.split()[1:4]]
                    lo = [min(a, b) for a, b in zip(lo, p)]
                    hi = [max(a, b) for a, b in zip(hi, p)]
    return lo, hi


def kuhn_background(lo, hi, cells):
    """Points of a cells^3 grid over [lo, hi] and six tets per cube around its main diagonal."""
    step = [(h - l) / cells for l, h in zip(lo, hi)]
    n = cells + 1
    points = [(lo[0] + i * step[0], lo[1] + j * step[1], lo[2] + k * step[2])
              for k in range(n) for j in range(n) for i in range(n)]
    index = lambda i, j, k: (k * n + j) * n + i
    tets = []
    for k, j, i in itertools.product(range(cells), repeat=3):
        for order in itertools.permutations(range(3)):
            corner, path = [i, j, k], [index(i, j, k)]
            for axis in order:
                corner[axis] += 1
                path.append(index(*corner))
            tets.append(path)
    return points, tets


def write_msh(path, points, tets, values):
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(points))
        for i, p in enumerate(points):
            f.write("%d %.17g %.17g %.17g\n" % (i + 1, *p))
        f.write("$EndNodes\n$Elements\n%d\n" % len(tets))
        for i, t in enumerate(tets):
            f.write("%d 4 2 1 1 %d %d %d %d\n" % (i + 1, *[v + 1 for v in t]))
        f.write('$EndElements\n$NodeData\n1\n"values"\n1\n0.0\n3\n0\n1\n%d\n' % len(points))
        for i, v in enumerate(values):
            f.write("%d %.17g\n" % (i + 1, v))
        f.write("$EndNodeData\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("model")
    parser.add_argument("--out", required=True)
    parser.add_argument("--fine", type=float, default=0.01, help="length near the point (default 0.01)")
    parser.add_argument("--coarse", type=float, default=0.05, help="length far from it (default 0.05)")
    parser.add_argument("--radius", type=float, default=0.2, help="radius of the fine ball (default 0.2)")
    parser.add_argument("--center", type=float, nargs=3, help="the point (default: the box centre)")
    parser.add_argument("--cells", type=int, default=16, help="background cubes per axis (default 16)")
    parser.add_argument("--build-dir", default="build")
    args = parser.parse_args()
    lo, hi = model_box(args.model, args.build_dir)
    diagonal = sum((h - l) ** 2 for l, h in zip(lo, hi)) ** 0.5
    if not diagonal > 0:
        sys.exit("%s: the model's box is empty" % args.model)
    margin = [0.1 * (h - l) + 1e-3 * diagonal for l, h in zip(lo, hi)]
    lo = [l - m for l, m in zip(lo, margin)]
    hi = [h + m for h, m in zip(hi, margin)]
    center = args.center or [(l + h) / 2 for l, h in zip(lo, hi)]
    radius = args.radius * diagonal
    points, tets = kuhn_background(lo, hi, args.cells)

    def value(p):
        distance = sum((a - c) ** 2 for a, c in zip(p, center)) ** 0.5
        t = min(max(distance / radius - 1, 0.0), 1.0)
        return diagonal * (args.fine + (args.coarse - args.fine) * t)

    write_msh(args.out, points, tets, [value(p) for p in points])


if __name__ == "__main__":
    main()
