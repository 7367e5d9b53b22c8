"""Finding the models of a batch (a folder, a glob, a list file or one file) and naming outputs."""
import glob
import os
from dataclasses import dataclass

# Formats the tools read (format-convert --help); .vtu is write-only, so not an input.
MESH_EXTENSIONS = (".stl", ".obj", ".off", ".ply", ".glb", ".gltf", ".drc", ".msh", ".mesh", ".vdb")
SURFACE_OUTPUTS = ("stl", "obj", "off", "ply", "glb", "gltf", "drc")
VOLUME_OUTPUTS = ("msh", "mesh", "vtu")
VOLUME_TOOLS = ("tetrahedralize",)


class InputError(Exception):
    """IN or OUT_DIR cannot be used; the message names the problem (exit code 2)."""


@dataclass
class Model:
    path: str  # absolute path of the input
    key: str  # path relative to the batch's base folder, with forward slashes
    size: int  # bytes
    output: str = ""  # absolute output path, set by plan_outputs


def discover(spec, out_dir):
    """The models named by spec, sorted by key; never inside out_dir."""
    if os.path.isdir(spec):
        paths, base = _walk(spec), spec
    elif glob.has_magic(spec):
        paths, base = _glob(spec), _glob_base(spec)
    elif os.path.isfile(spec):
        if _is_mesh(spec):
            paths, base = [spec], os.path.dirname(os.path.abspath(spec))
        else:
            paths = read_list_file(spec)
            base = _list_base(spec, paths)
    else:
        raise InputError(f"{spec}: no such folder, file or matching glob")
    out_dir = os.path.realpath(out_dir)
    models, seen = [], set()
    for path in paths:
        real = os.path.realpath(path)
        if real in seen or _inside(real, out_dir):
            continue
        seen.add(real)
        key = os.path.relpath(os.path.abspath(path), os.path.abspath(base)).replace(os.sep, "/")
        models.append(Model(os.path.abspath(path), key, os.path.getsize(path)))
    if not models:
        raise InputError(f"{spec}: no mesh files found (extensions: {' '.join(MESH_EXTENSIONS)})")
    return sorted(models, key=lambda m: m.key)


def read_list_file(path):
    """Paths listed one per line, relative to the list's folder; blank lines and lines starting with #
    are skipped."""
    folder = os.path.dirname(os.path.abspath(path))
    paths, missing = [], []
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: cannot read the list file: {e}") from e
    for number, line in enumerate(lines, 1):
        entry = line.strip()
        if not entry or entry.startswith("#"):
            continue
        full = os.path.join(folder, os.path.expanduser(entry))
        if not os.path.isfile(full):
            missing.append(f"line {number}: {entry}")
        else:
            paths.append(full)
    if missing:
        shown = "; ".join(missing[:5]) + (f"; and {len(missing) - 5} more" if len(missing) > 5 else "")
        raise InputError(f"{path}: {len(missing)} listed file(s) not found: {shown}")
    return paths


def plan_outputs(models, out_dir, tool, to=None):
    """Sets each model's output path: OUT_DIR/<key with the new extension>. Two inputs that would
    share an output (a.stl and a.obj to a.glb) keep their extension in the name (a.stl.glb)."""
    out_dir = os.path.abspath(out_dir)
    targets = {}
    for m in models:
        ext = output_extension(m.path, tool, to)
        stem = os.path.splitext(m.key)[0]
        targets.setdefault(stem + "." + ext, []).append((m, ext))
    for name, group in targets.items():
        for m, ext in group:
            rel = name if len(group) == 1 else f"{m.key}.{ext}"
            m.output = os.path.join(out_dir, *rel.split("/"))
    return models


def output_extension(path, tool, to=None):
    """--to if given, else .msh for tetrahedralize, else the input's (.obj for a volume input)."""
    if to:
        return to
    if tool in VOLUME_TOOLS:
        return "msh"
    ext = os.path.splitext(path)[1].lower().lstrip(".")
    return ext if ext in SURFACE_OUTPUTS else "obj"


def check_extension(tool, to):
    """The --to value, normalized; InputError when the tool cannot write it."""
    if to is None:
        return None
    to = to.lower().lstrip(".")
    allowed = VOLUME_OUTPUTS if tool in VOLUME_TOOLS else SURFACE_OUTPUTS
    if to not in allowed:
        raise InputError(f"--to {to}: {tool} writes {', '.join(allowed)}")
    return to


def _walk(folder):
    found = []
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        found += [os.path.join(root, f) for f in sorted(files) if _is_mesh(f) and not f.startswith(".")]
    return found


def _list_base(list_file, paths):
    """The list's folder when every listed file is under it, else the listed files' common folder."""
    folder = os.path.dirname(os.path.abspath(list_file))
    if all(_inside(os.path.abspath(p), folder) for p in paths):
        return folder
    return os.path.commonpath([os.path.dirname(os.path.abspath(p)) for p in paths]) if paths else folder


def _glob(pattern):
    return sorted(p for p in glob.glob(pattern, recursive=True) if os.path.isfile(p) and _is_mesh(p))


def _glob_base(pattern):
    """The folder part of a glob before its first wildcard."""
    parts = pattern.split(os.sep)
    fixed = []
    for part in parts[:-1]:
        if glob.has_magic(part):
            break
        fixed.append(part)
    return os.sep.join(fixed) or (os.sep if pattern.startswith(os.sep) else ".")


def _is_mesh(path):
    return os.path.splitext(path)[1].lower() in MESH_EXTENSIONS


def _inside(path, folder):
    return path == folder or path.startswith(folder.rstrip(os.sep) + os.sep)
