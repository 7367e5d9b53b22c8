#!/usr/bin/env python3
"""Writes the small example models in models/. We made them; they are CC0.

Each is broken the way real inputs are: a box missing a face and carrying a
duplicated facet (binary STL), two boxes overlapping each other (OBJ), and a
torus stored as a soup of disconnected triangles with some flipped (ASCII PLY).
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def box(lo, hi):
    v = [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]) for i in range(8)]
    f = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
         (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]
    return v, f


def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    w = [c[i] - a[i] for i in range(3)]
    n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
    length = math.sqrt(sum(x * x for x in n)) or 1.0
    return tuple(x / length for x in n)


def write_binary_stl(path, vertices, faces):
    with open(path, "wb") as out:
        out.write(b"box with a hole and a duplicated facet".ljust(80, b" "))
        out.write(struct.pack("<I", len(faces)))
        for f in faces:
            a, b, c = (vertices[i] for i in f)
            out.write(struct.pack("<12fH", *normal(a, b, c), *a, *b, *c, 0))


def box_with_hole():
    v, f = box((0, 0, 0), (40, 30, 20))
    f = [t for k, t in enumerate(f) if k not in (2, 3)]  # open top
    f.append(f[0])  # a duplicated facet
    write_binary_stl(os.path.join(HERE, "models", "box_with_hole.stl"), v, f)


def overlapping_boxes():
    a_v, a_f = box((0, 0, 0), (2, 2, 2))
    b_v, b_f = box((1, 1, 1), (3, 3, 3))
    lines = ["# two boxes overlapping each other: a self-intersecting surface"]
    lines += ["v %g %g %g" % p for p in a_v + b_v]
    lines += ["f %d %d %d" % tuple(i + 1 for i in t) for t in a_f]
    lines += ["f %d %d %d" % tuple(i + 9 for i in t) for t in b_f]
    with open(os.path.join(HERE, "models", "overlapping_boxes.obj"), "w") as out:
        out.write("\n".join(lines) + "\n")


def torus_soup(rings=24, sides=12, big=3.0, small=1.0):
    def point(i, j):
        u, v = 2 * math.pi * i / rings, 2 * math.pi * j / sides
        r = big + small * math.cos(v)
        return (r * math.cos(u), r * math.sin(u), small * math.sin(v))

    triangles = []
    for i in range(rings):
        for j in range(sides):
            a, b = point(i, j), point(i + 1, j)
            c, d = point(i + 1, j + 1), point(i, j + 1)
            triangles += [(a, b, c), (a, c, d)]
    triangles = [(t[0], t[2], t[1]) if k % 7 == 0 else t for k, t in enumerate(triangles)]  # flip some
    with open(os.path.join(HERE, "models", "torus_soup.ply"), "w") as out:
        out.write("ply\nformat ascii 1.0\ncomment torus as a soup: no shared vertices, some faces flipped\n")
        out.write("element vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % (3 * len(triangles)))
        out.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(triangles))
        for t in triangles:
            for p in t:
                out.write("%.6f %.6f %.6f\n" % p)
        for k in range(len(triangles)):
            out.write("3 %d %d %d\n" % (3 * k, 3 * k + 1, 3 * k + 2))


if __name__ == "__main__":
    os.makedirs(os.path.join(HERE, "models"), exist_ok=True)
    box_with_hole()
    overlapping_boxes()
    torus_soup()
