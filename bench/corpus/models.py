"""The models of a corpus folder: the rows of its MANIFEST.tsv, or every mesh file under it."""
import csv
import fnmatch
import os
import sys
from dataclasses import dataclass

MESH_EXTENSIONS = (".stl", ".obj", ".off", ".ply", ".glb", ".gltf")


@dataclass(frozen=True)
class Model:
    key: str  # relative path with '/' -> '__' and no extension (baseline.tsv's 'model')
    relpath: str
    path: str
    tags: tuple
    faces: int | None  # from the manifest; None = measure it
    bytes: int


def model_key(relpath):
    stem, _ = os.path.splitext(relpath.replace(os.sep, "/"))
    return stem.replace("/", "__")


def _parse_int(text):
    try:
        return int(text)
    except (TypeError, ValueError):
        return None


def _split_tags(text):
    return tuple(t.strip() for t in (text or "").split(",") if t.strip())


def _make_model(folder, relpath, tags=(), faces=None):
    path = os.path.join(folder, relpath)
    return Model(model_key(relpath), relpath, path, tags, faces, os.path.getsize(path))


def _from_manifest(folder, manifest):
    models = []
    with open(manifest, newline="", encoding="utf-8") as f:
        for row in csv.DictReader(f, delimiter="\t"):
            relpath = (row.get("file") or "").strip()
            if not relpath:
                continue
            if not os.path.isfile(os.path.join(folder, relpath)):
                print(f"warning: {manifest} lists {relpath}, which does not exist; skipped", file=sys.stderr)
                continue
            models.append(_make_model(folder, relpath, _split_tags(row.get("tags")), _parse_int(row.get("faces"))))
    return models


def _from_walk(folder):
    models = []
    for root, dirs, files in os.walk(folder):
        dirs.sort()
        for name in sorted(files):
            if name.lower().endswith(MESH_EXTENSIONS):
                models.append(_make_model(folder, os.path.relpath(os.path.join(root, name), folder)))
    return models


def discover(folder):
    """MANIFEST.tsv rows if the folder has one, else every mesh file under it (no tags)."""
    folder = os.path.abspath(folder)
    manifest = os.path.join(folder, "MANIFEST.tsv")
    models = _from_manifest(folder, manifest) if os.path.isfile(manifest) else _from_walk(folder)
    keys = {}
    for m in models:
        if m.key in keys:
            raise ValueError(f"two models map to the key {m.key}: {keys[m.key]} and {m.relpath}")
        keys[m.key] = m.relpath
    return models


def select(models, globs):
    """Models whose relative path or key matches one of the globs (all if none given)."""
    if not globs:
        return list(models)
    return [m for m in models if any(fnmatch.fnmatch(m.relpath, g) or fnmatch.fnmatch(m.key, g) for g in globs)]
