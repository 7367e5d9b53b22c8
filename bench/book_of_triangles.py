#!/usr/bin/env python3
"""Write a stress model for triangle insertion: a unit cube holding a "book"
of N long triangles whose spines nearly coincide (1e-7 apart), so every page
crosses the others close to one line. The cut points grow steeply with N
(session 8, meshrepair without lattice: N=8 2,345 cut points, 12 14,359,
16 52,869; N=24 did not finish inserting in 150 s).

    bench/book_of_triangles.py 16 book16.obj
    meshrepair book16.obj out.ply -v --skip-simplify
"""
import argparse
import math


def book(pages):
    vertices = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    faces = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
             (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    for i in range(pages):
        angle = 0.13 * i + 0.01
        offset = 1e-7 * i
        base = len(vertices)
        vertices += [(0.05, 0.5 + 3 * offset, 0.5 - offset),
                     (0.95, 0.5 - offset, 0.5 + 2 * offset),
                     (0.5, 0.5 + 0.45 * math.cos(angle), 0.5 + 0.45 * math.sin(angle))]
        faces.append((base, base + 1, base + 2))
    return vertices, faces


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("pages", type=int)
    parser.add_argument("out", help="OBJ file to write")
    args = parser.parse_args()
    vertices, faces = book(args.pages)
    with open(args.out, "w") as f:
        for v in vertices:
            f.write("v %.17g %.17g %.17g\n" % v)
        for t in faces:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


if __name__ == "__main__":
    main()
