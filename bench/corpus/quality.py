"""Radius ratio of tet meshes (mesh-check does not report it yet).

The mesh is read from a Medit .mesh file (ASCII, as format-convert and TetGen -g write it).
Normalized radius ratio rho = 3 * inradius / circumradius: 1 for the regular tet, 0 for a
flat one.
"""
import re

import numpy as np

MAX_TETS = 5_000_000  # beyond this the column stays empty (memory and time of parsing text)


def _section(text, keyword, width):
    """(count, width) array of the numbers following a Medit keyword line, or None."""
    found = re.search(rb"^[ \t]*" + keyword + rb"[ \t]*\r?\n[ \t]*(\d+)[ \t]*\r?$", text, re.M)
    if not found:
        return None
    count = int(found.group(1))
    if count > MAX_TETS * 4:
        return None
    values = np.fromstring(text[found.end():].decode("ascii", "replace"), sep=" ", count=count * width)
    if len(values) != count * width:
        return None
    return values.reshape(count, width)


def read_medit_tets(path):
    """(points, tets) from an ASCII Medit file, or None if it has no tets or is too large."""
    with open(path, "rb") as f:
        text = f.read()
    text = re.sub(rb"#[^\n]*", b"", text)  # comments may hold keywords ("# Set of Tetrahedra")
    tets = _section(text, b"Tetrahedra", 5)
    if tets is None or len(tets) == 0 or len(tets) > MAX_TETS:
        return None
    points = _section(text, b"Vertices", 4)
    if points is None:
        return None
    return points[:, :3], tets[:, :4].astype(np.int64) - 1


def radius_ratios(points, tets):
    a, b, c, d = (points[tets[:, i]] for i in range(4))
    u, v, w = b - a, c - a, d - a
    det = np.einsum("ij,ij->i", u, np.cross(v, w))
    volume = np.abs(det) / 6.0
    area = sum(0.5 * np.linalg.norm(np.cross(p, q), axis=1)
               for p, q in ((u, v), (v, w), (w, u), (c - b, d - b)))
    offset = (np.einsum("ij,ij->i", u, u)[:, None] * np.cross(v, w)
              + np.einsum("ij,ij->i", v, v)[:, None] * np.cross(w, u)
              + np.einsum("ij,ij->i", w, w)[:, None] * np.cross(u, v))
    with np.errstate(divide="ignore", invalid="ignore"):
        circumradius = np.linalg.norm(offset, axis=1) / np.abs(2.0 * det)
        inradius = 3.0 * volume / area
        rho = 3.0 * inradius / circumradius
    return np.nan_to_num(rho, nan=0.0, posinf=0.0, neginf=0.0)


def radius_ratio_summary(medit_path):
    """{'min_radius_ratio', 'avg_radius_ratio'} or {} when the file cannot be used."""
    try:
        mesh = read_medit_tets(medit_path)
    except (OSError, ValueError, IndexError):
        return {}
    if mesh is None:
        return {}
    points, tets = mesh
    if tets.min() < 0 or tets.max() >= len(points):
        return {}
    rho = radius_ratios(points, tets)
    return {"min_radius_ratio": float(rho.min()), "avg_radius_ratio": float(rho.mean())}
