"""Meshes built in code for the tests of the Python module `meshrepair`.

The module is imported from the build folder: ctest sets PYTHONPATH to it
(build/python); by hand, `PYTHONPATH=build/python /usr/bin/python3 -m pytest tests/python`.
"""

import numpy as np
import pytest

# The unit cube [0, 1]^3, faces outward: two triangles per side.
CUBE_VERTICES = np.array(
    [[x, y, z] for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)], dtype=np.float64
)
CUBE_FACES = np.array(
    [
        [0, 1, 3], [0, 3, 2],  # x = 0
        [4, 6, 7], [4, 7, 5],  # x = 1
        [0, 4, 5], [0, 5, 1],  # y = 0
        [2, 3, 7], [2, 7, 6],  # y = 1
        [0, 2, 6], [0, 6, 4],  # z = 0
        [1, 5, 7], [1, 7, 3],  # z = 1
    ],
    dtype=np.int64,
)


def signed_volume(vertices, faces):
    """Volume enclosed by a closed, outward surface (divergence theorem)."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def tet_volumes(vertices, tets):
    """Signed volume of each tet; positive for the library's orientation."""
    a, b, c, d = (vertices[tets[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0


def subdivided_cube(n):
    """The unit cube with each side split into n x n squares (2 n^2 triangles a side)."""
    vertices, faces = [], []
    ticks = np.linspace(0.0, 1.0, n + 1)
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for side in (0.0, 1.0):
            base = len(vertices)
            for i in ticks:
                for j in ticks:
                    p = [0.0, 0.0, 0.0]
                    p[axis], p[u], p[v] = side, i, j
                    vertices.append(p)
            for i in range(n):
                for j in range(n):
                    q = [base + i * (n + 1) + j, base + (i + 1) * (n + 1) + j,
                         base + (i + 1) * (n + 1) + j + 1, base + i * (n + 1) + j + 1]
                    # (u, v) is right-handed around +axis: outward on side 1, flipped on side 0.
                    tris = [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
                    faces.extend(tris if side == 1.0 else [t[::-1] for t in tris])
    return np.array(vertices), np.array(faces, dtype=np.int64)


@pytest.fixture
def cube():
    return CUBE_VERTICES.copy(), CUBE_FACES.copy()


@pytest.fixture
def soup_cube():
    """The cube as an STL-like soup: every triangle with its own three
    vertices, and every triangle given twice."""
    vertices = CUBE_VERTICES[CUBE_FACES.reshape(-1)]
    faces = np.arange(len(vertices), dtype=np.int32).reshape(-1, 3)
    return vertices, np.concatenate([faces, faces])


@pytest.fixture
def open_cube():
    """The cube without its top (z = 1): one square hole of four border edges."""
    return CUBE_VERTICES.copy(), CUBE_FACES[:10].copy()
