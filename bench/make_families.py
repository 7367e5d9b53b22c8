#!/usr/bin/python3
"""Seeded defect families of the closed corpus models, for bench/run_corpus.py --corpus OUT.

Every model of a corpus whose MANIFEST.tsv says closed == 1 becomes up to four files:
- soup: every triangle with its own 3 corners, triangles shuffled, corners rotated (orientation
  kept); binary STL (float32 corners);
- soup_dup_flip: the soup plus 10% of the triangles duplicated and 5% flipped; binary STL;
- jitter: the welded model, every vertex moved by a random vector of length 0.5 eps (eps = 1e-3 of
  the bbox diagonal); OBJ with %.17g coordinates (exact);
- overlap: the welded model and a copy translated by a third of the bbox diagonal vector, so that
  the two overlap and intersect; OBJ with %.17g coordinates.
- far (only when asked for): the welded model moved 1e5 times its bbox diagonal from the origin in a
  random direction, where float32 steps exceed epsilon; OBJ with %.17g coordinates.
- graze (only when asked for): the welded model and a nearly coincident copy, turned by 0.002 rad
  about a random axis through the bbox centre and moved by 0.5 eps in a random direction, so that
  the two surfaces cross each other at grazing angles everywhere (assemblies with coincident faces,
  a model exported twice); OBJ with %.17g coordinates.
Files land under OUT with the corpus's relative layout and the family before the extension
(OUT/thingi10k/100036.soup.stl), with OUT/MANIFEST.tsv listing them. Inputs are read through our
format-convert (any corpus format -> OBJ). The same --seed gives the same bytes.

    bench/make_families.py --out /tmp/families --models 'thingi10k/*' --families soup,jitter
"""
import argparse
import csv
import fnmatch
import hashlib
import os
import subprocess
import sys
import tempfile


def _reexec_with_debian_python():
    """numpy comes from Debian's python3; another python3 on PATH may lack it."""
    debian = "/usr/bin/python3"
    if os.path.realpath(sys.executable) != os.path.realpath(debian) and os.access(debian, os.X_OK):
        os.execv(debian, [debian] + sys.argv)


try:
    import numpy as np
except ImportError:
    if __name__ != "__main__":
        raise
    _reexec_with_debian_python()
    raise

BENCH_DIR = os.path.dirname(os.path.abspath(__file__))
REPO_DIR = os.path.dirname(BENCH_DIR)
DEFAULT_CORPUS = os.path.normpath(os.path.join(REPO_DIR, "..", "shared", "corpus"))
FAMILIES = ("soup", "soup_dup_flip", "jitter", "overlap", "graze", "far")
DEFAULT_FAMILIES = FAMILIES[:4]
EXTENSION = {"soup": ".stl", "soup_dup_flip": ".stl", "jitter": ".obj", "overlap": ".obj", "graze": ".obj",
             "far": ".obj"}
TAGS = {"soup": "soup,unwelded", "soup_dup_flip": "soup_dup_flip,unwelded,duplicate-faces,flipped-faces",
        "jitter": "jitter,perturbed", "overlap": "overlap,self-intersecting,multi-component",
        "graze": "graze,self-intersecting,multi-component,near-coincident", "far": "far-from-origin"}
DUPLICATED, FLIPPED = 0.10, 0.05  # fractions of the triangles in soup_dup_flip
JITTER = 0.5  # of epsilon
GRAZE_ANGLE, GRAZE_SHIFT = 0.002, 0.5  # radians; of epsilon
FAR = 1e5  # of the bbox diagonal
EPSILON = 1e-3  # of the bbox diagonal
MANIFEST_COLUMNS = ("file", "format", "bytes", "source", "license", "attribution", "family", "original",
                    "vertices", "faces", "boundary_edges", "closed", "tags")


# ---------------------------------------------------------------- reading

def parse_obj(text):
    """(vertices float64 (n, 3), triangles int64 (m, 3)) of an OBJ text; polygons fanned, v/vt/vn and
    negative indices understood, everything but 'v' and 'f' ignored."""
    vertices, triangles = [], []
    for line in text.splitlines():
        fields = line.split()
        if not fields:
            continue
        if fields[0] == "v":
            vertices.append([float(x) for x in fields[1:4]])
        elif fields[0] == "f":
            corners = [_obj_index(f, len(vertices)) for f in fields[1:]]
            triangles += [[corners[0], corners[i], corners[i + 1]] for i in range(1, len(corners) - 1)]
    return (np.array(vertices, dtype=np.float64).reshape(-1, 3),
            np.array(triangles, dtype=np.int64).reshape(-1, 3))


def _obj_index(field, count):
    index = int(field.split("/")[0])
    return index - 1 if index > 0 else count + index


def read_mesh(path, format_convert):
    """(vertices, triangles) of any mesh file our readers read, through format-convert -> OBJ."""
    with tempfile.TemporaryDirectory(prefix="families-") as tmp:
        obj = os.path.join(tmp, "mesh.obj")
        result = subprocess.run([format_convert, path, obj], capture_output=True, text=True)
        if result.returncode != 0 or not os.path.exists(obj):
            raise RuntimeError(f"format-convert failed on {path}: {result.stderr.strip()[-300:]}")
        with open(obj, encoding="utf-8") as f:
            return parse_obj(f.read())


def weld(vertices, triangles):
    """Identical positions merged, unreferenced vertices dropped; vertices in first-use order."""
    if len(triangles) == 0:
        return vertices[:0], triangles
    corners = vertices[triangles.reshape(-1)]
    unique, first, inverse = np.unique(corners, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")
    rank = np.empty(len(order), dtype=np.int64)
    rank[order] = np.arange(len(order))
    return unique[order], rank[inverse.reshape(-1)].reshape(-1, 3)


# ---------------------------------------------------------------- families

def family_rng(seed, relpath, family):
    """A RandomState (stream frozen across numpy versions) for one model and family."""
    digest = hashlib.sha256(f"{seed}\0{relpath}\0{family}".encode("utf-8")).digest()
    return np.random.RandomState(np.frombuffer(digest, dtype="<u4"))


def corners_of(vertices, triangles):
    """(m, 3, 3) array: the three corner positions of every triangle."""
    return vertices[triangles]


def shuffle_and_rotate(corners, rng):
    """Triangles in random order, each one's corners cyclically shifted by 0, 1 or 2 (orientation kept)."""
    shuffled = corners[rng.permutation(len(corners))]
    shift = rng.randint(0, 3, size=len(shuffled))
    order = (np.arange(3)[None, :] + shift[:, None]) % 3
    return shuffled[np.arange(len(shuffled))[:, None], order]


def soup(vertices, triangles, rng):
    return shuffle_and_rotate(corners_of(vertices, triangles), rng)


def soup_dup_flip(vertices, triangles, rng):
    """Soup of the model with FLIPPED of the triangles reversed and DUPLICATED of them (after the flips)
    appearing twice."""
    corners = corners_of(vertices, triangles).copy()
    count = len(corners)
    flipped = rng.choice(count, int(round(FLIPPED * count)), replace=False)
    corners[flipped] = corners[flipped][:, ::-1]
    duplicated = rng.choice(count, int(round(DUPLICATED * count)), replace=False)
    return shuffle_and_rotate(np.concatenate([corners, corners[duplicated]]), rng)


def bbox_diagonal(vertices):
    return float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))


def jitter(vertices, triangles, rng):
    """Every vertex moved by a random direction times JITTER * EPSILON * the bbox diagonal."""
    step = JITTER * EPSILON * bbox_diagonal(vertices)
    directions = rng.standard_normal(vertices.shape)
    lengths = np.linalg.norm(directions, axis=1, keepdims=True)
    directions = np.where(lengths > 0, directions / np.where(lengths > 0, lengths, 1), [1.0, 0.0, 0.0])
    return vertices + step * directions, triangles


def overlap(vertices, triangles, rng=None):
    """The model and a copy moved by a third of its bbox diagonal vector (max - min)."""
    shift = (vertices.max(axis=0) - vertices.min(axis=0)) / 3.0
    return (np.concatenate([vertices, vertices + shift]),
            np.concatenate([triangles, triangles + len(vertices)]))


def random_unit_vector(rng):
    while True:
        v = rng.standard_normal(3)
        if np.linalg.norm(v) > 1e-6:
            return v / np.linalg.norm(v)


def rotation(axis, angle):
    """The 3x3 matrix turning by `angle` about the unit vector `axis` (Rodrigues)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


def graze(vertices, triangles, rng):
    """The model and a copy turned by GRAZE_ANGLE about a random axis through the bbox centre, then moved
    by GRAZE_SHIFT * EPSILON * the bbox diagonal in a random direction."""
    centre = 0.5 * (vertices.max(axis=0) + vertices.min(axis=0))
    turn = rotation(random_unit_vector(rng), GRAZE_ANGLE)
    shift = GRAZE_SHIFT * EPSILON * bbox_diagonal(vertices) * random_unit_vector(rng)
    copy = (vertices - centre) @ turn.T + centre + shift
    return (np.concatenate([vertices, copy]),
            np.concatenate([triangles, triangles + len(vertices)]))


def far(vertices, triangles, rng):
    """The model moved FAR times its bbox diagonal from the origin, in a random direction: float32 steps
    there are about 1.2e-2 of its size, twelve times epsilon (georeferenced scans, CAD parts placed in a
    plant's coordinates)."""
    return vertices + FAR * bbox_diagonal(vertices) * random_unit_vector(rng), triangles


MAKERS = {"soup": soup, "soup_dup_flip": soup_dup_flip, "jitter": jitter, "overlap": overlap, "graze": graze,
          "far": far}


# ---------------------------------------------------------------- writing

def stl_header(text):
    """80 bytes that do not start with 'solid' (readers would take the file for ASCII STL)."""
    data = text.encode("ascii", "replace")
    if data.lstrip().lower().startswith(b"solid"):
        data = b"binary STL: " + data
    return data[:80].ljust(80, b" ")


def write_binary_stl(path, corners, header):
    """Binary STL of (m, 3, 3) corners (float32), with unit normals computed from the float32 corners."""
    record = np.dtype([("normal", "<f4", (3,)), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    data = np.zeros(len(corners), dtype=record)
    data["corners"] = corners
    stored = data["corners"].astype(np.float64)
    normals = np.cross(stored[:, 1] - stored[:, 0], stored[:, 2] - stored[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    data["normal"] = np.where(lengths > 0, normals / np.where(lengths > 0, lengths, 1), 0.0)
    with open(path, "wb") as f:
        f.write(stl_header(header))
        f.write(np.uint32(len(corners)).astype("<u4").tobytes())
        f.write(data.tobytes())


def write_obj(path, vertices, triangles, comment):
    """OBJ with %.17g coordinates (every double exact), 1-based triangles."""
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write(f"# {comment}\n")
        f.writelines("v %.17g %.17g %.17g\n" % tuple(v) for v in vertices.tolist())
        f.writelines("f %d %d %d\n" % tuple(t) for t in (triangles + 1).tolist())


def boundary_edges(triangles):
    """Number of undirected edges used by exactly one triangle (of a welded mesh); the zero-length edge
    of a triangle with a repeated corner is no edge."""
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    edges = edges[edges[:, 0] != edges[:, 1]]
    if len(edges) == 0:
        return 0
    _, counts = np.unique(np.sort(edges, axis=1), axis=0, return_counts=True)
    return int(np.sum(counts == 1))


# ---------------------------------------------------------------- one model

def family_path(relpath, family):
    stem, _ = os.path.splitext(relpath)
    return f"{stem}.{family}{EXTENSION[family]}"


def make_family(vertices, triangles, relpath, family, seed, out_dir):
    """Writes one family file of a welded model; returns its manifest row."""
    rng = family_rng(seed, relpath, family)
    rel = family_path(relpath, family)
    path = os.path.join(out_dir, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    comment = f"{family} of {relpath}, make_families.py --seed {seed}"
    made = MAKERS[family](vertices, triangles, rng)
    if EXTENSION[family] == ".stl":
        write_binary_stl(path, made, comment)
        stored = made.astype(np.float32).astype(np.float64).reshape(-1, 3)
        welded = weld(stored, np.arange(len(stored)).reshape(-1, 3))[1]
        count_vertices, count_faces = len(stored), len(made)
    else:
        write_obj(path, made[0], made[1], comment)
        welded = made[1]
        count_vertices, count_faces = len(made[0]), len(made[1])
    boundary = boundary_edges(welded)
    return {"file": rel.replace(os.sep, "/"), "format": EXTENSION[family].lstrip("."),
            "bytes": os.path.getsize(path), "family": family, "original": relpath,
            "source": f"{family} of corpus {relpath} (bench/make_families.py --seed {seed})",
            "vertices": count_vertices, "faces": count_faces, "boundary_edges": boundary,
            "closed": int(boundary == 0), "tags": TAGS[family]}


# ---------------------------------------------------------------- corpus

def closed_models(corpus):
    """MANIFEST.tsv rows of the corpus with closed == 1."""
    with open(os.path.join(corpus, "MANIFEST.tsv"), newline="", encoding="utf-8") as f:
        return [row for row in csv.DictReader(f, delimiter="\t") if (row.get("closed") or "").strip() == "1"]


def _model_key(relpath):
    return os.path.splitext(relpath)[0].replace("/", "__")


def select(rows, globs, max_faces):
    """Rows whose file or key matches one of the globs (all without globs), with at most max_faces."""
    chosen = []
    for row in rows:
        relpath = row["file"]
        if globs and not any(fnmatch.fnmatch(relpath, g) or fnmatch.fnmatch(_model_key(relpath), g) for g in globs):
            continue
        faces = row.get("faces") or ""
        if max_faces is not None and faces.isdigit() and int(faces) > max_faces:
            continue
        chosen.append(row)
    return chosen


def write_manifest(out_dir, rows):
    with open(os.path.join(out_dir, "MANIFEST.tsv"), "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, MANIFEST_COLUMNS, delimiter="\t", lineterminator="\n", extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)


def generate(corpus, out_dir, families, seed, format_convert, globs=(), max_faces=None, log=print):
    """Writes every family of every selected closed model and OUT/MANIFEST.tsv; returns the rows."""
    os.makedirs(out_dir, exist_ok=True)
    manifest = []
    for original in select(closed_models(corpus), globs, max_faces):
        relpath = original["file"]
        try:
            vertices, triangles = weld(*read_mesh(os.path.join(corpus, relpath), format_convert))
        except RuntimeError as e:
            log(f"warning: {e}; skipped")
            continue
        for family in families:
            row = make_family(vertices, triangles, relpath, family, seed, out_dir)
            row.update(license=original.get("license", ""), attribution=original.get("attribution", ""))
            manifest.append(row)
            log(f"{row['file']}: {row['faces']} faces, {row['boundary_edges']} boundary edges")
    write_manifest(out_dir, manifest)
    return manifest


def parse_args(argv):
    p = argparse.ArgumentParser(prog="make_families.py", description=__doc__.split("\n\n")[0])
    p.add_argument("--out", required=True, help="output folder (gets the files and MANIFEST.tsv)")
    p.add_argument("--corpus", default=DEFAULT_CORPUS, help="corpus folder with MANIFEST.tsv (default: %(default)s)")
    p.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    p.add_argument("--families", default=",".join(DEFAULT_FAMILIES),
                   help=f"comma list of {', '.join(FAMILIES)} (default: all but graze and far)")
    p.add_argument("--models", action="append", default=[], metavar="GLOB",
                   help="only models whose relative path or key matches (repeatable)")
    p.add_argument("--max-faces", type=int, help="only models with at most this many faces (MANIFEST's faces)")
    p.add_argument("--build-dir", default=os.environ.get("MR_BUILD_DIR", os.path.join(REPO_DIR, "build")),
                   help="CMake build folder with format-convert (default: $MR_BUILD_DIR or build/)")
    p.add_argument("--format-convert", help="format-convert executable (default: in --build-dir)")
    args = p.parse_args(argv)
    args.families = [f.strip() for f in args.families.split(",") if f.strip()]
    unknown = [f for f in args.families if f not in FAMILIES]
    if unknown or not args.families:
        p.error(f"--families: unknown {', '.join(unknown) or '(none)'}; known: {', '.join(FAMILIES)}")
    args.out, args.corpus = os.path.abspath(args.out), os.path.abspath(args.corpus)
    args.format_convert = os.path.abspath(args.format_convert or os.path.join(
        args.build_dir, "tools", "format-convert", "format-convert"))
    if not os.access(args.format_convert, os.X_OK):
        p.error(f"format-convert not found at {args.format_convert} (use --build-dir or --format-convert)")
    return args


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    rows = generate(args.corpus, args.out, args.families, args.seed, args.format_convert, args.models, args.max_faces)
    if not rows:
        print(f"no closed model of {args.corpus} selected", file=sys.stderr)
        return 1
    print(f"{len(rows)} files and MANIFEST.tsv in {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
