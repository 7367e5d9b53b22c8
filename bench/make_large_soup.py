#!/usr/bin/python3
"""Large triangle soups from a corpus model, for the scaling bench (issue 26).

The model is split 1-to-4 (edge midpoints) until it has at least --faces
triangles, then turned into a soup: every triangle gets its own three
vertices, the triangles are shuffled, and optionally a fraction is flipped
or duplicated. Written as binary STL (float32), the format soups arrive in.

  bench/make_large_soup.py /work/shared/corpus/c3d/igea.ply --faces 1000000 --out igea_1m.stl
"""
import argparse
import os
import pathlib
import struct
import subprocess
import sys
import tempfile

import meshio
import numpy as np


def read_mesh(path, format_convert):
    """meshio's reading, or ours through an OBJ where meshio cannot (e.g. PLY triangle strips)."""
    try:
        return meshio.read(path)
    except (Exception, SystemExit):  # meshio raises, or exits, in several ways
        with tempfile.TemporaryDirectory() as folder:
            obj = pathlib.Path(folder) / "model.obj"
            subprocess.run([str(format_convert), str(path), str(obj)], check=True)
            return meshio.read(obj)


def read_triangles(path, format_convert):
    """Vertices (float64 Nx3) and triangles (int64 Mx3) of a mesh file."""
    mesh = read_mesh(path, format_convert)
    triangles = [block.data for block in mesh.cells if block.type == "triangle"]
    if not triangles:
        sys.exit(f"{path}: no triangles")
    return np.asarray(mesh.points[:, :3], dtype=np.float64), np.concatenate(triangles).astype(np.int64)


def split_one_to_four(vertices, faces):
    """Each triangle into four through its edge midpoints, shared midpoints welded."""
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    edges.sort(axis=1)
    unique_edges, edge_of = np.unique(edges, axis=0, return_inverse=True)
    midpoints = 0.5 * (vertices[unique_edges[:, 0]] + vertices[unique_edges[:, 1]])
    m = edge_of.reshape(3, -1) + len(vertices)
    a, b, c = faces[:, 0], faces[:, 1], faces[:, 2]
    ab, bc, ca = m[0], m[1], m[2]
    new_faces = np.concatenate([
        np.stack([a, ab, ca], axis=1),
        np.stack([ab, b, bc], axis=1),
        np.stack([ca, bc, c], axis=1),
        np.stack([ab, bc, ca], axis=1),
    ])
    return np.concatenate([vertices, midpoints]), new_faces


def make_soup(vertices, faces, rng, flip_fraction, duplicate_fraction):
    """Corner positions (Mx3x3): unwelded, shuffled, some flipped, some repeated."""
    corners = vertices[faces]
    flip = rng.random(len(corners)) < flip_fraction
    corners[flip] = corners[flip][:, ::-1, :]
    duplicates = corners[rng.random(len(corners)) < duplicate_fraction]
    corners = np.concatenate([corners, duplicates])
    return corners[rng.permutation(len(corners))]


def write_binary_stl(path, corners):
    """Binary STL with zero normals (readers recompute them)."""
    records = np.zeros(len(corners), dtype=[("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attr", "<u2")])
    records["corners"] = corners.astype(np.float32)
    with open(path, "wb") as out:
        out.write(b"large soup from bench/make_large_soup.py".ljust(80, b" "))
        out.write(struct.pack("<I", len(records)))
        records.tofile(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("model", type=pathlib.Path)
    parser.add_argument("--faces", type=int, required=True, help="at least this many triangles (before duplicates)")
    parser.add_argument("--out", type=pathlib.Path, required=True, help="binary STL to write")
    parser.add_argument("--flip", type=float, default=0.0, help="fraction of triangles flipped (default 0)")
    parser.add_argument("--duplicate", type=float, default=0.0, help="fraction of triangles repeated (default 0)")
    parser.add_argument("--seed", type=int, default=1)
    default_build = pathlib.Path(os.environ.get("MR_BUILD_DIR", pathlib.Path(__file__).parent.parent / "build"))
    parser.add_argument("--format-convert", type=pathlib.Path,
                        default=default_build / "tools/format-convert/format-convert",
                        help="reads what meshio cannot (default: in $MR_BUILD_DIR or build/)")
    args = parser.parse_args()

    vertices, faces = read_triangles(args.model, args.format_convert)
    while len(faces) < args.faces:
        vertices, faces = split_one_to_four(vertices, faces)
    corners = make_soup(vertices, faces, np.random.default_rng(args.seed), args.flip, args.duplicate)
    write_binary_stl(args.out, corners)
    print(f"{args.out}: {len(corners)} triangles from {args.model} ({len(faces)} after splitting)")


if __name__ == "__main__":
    main()
