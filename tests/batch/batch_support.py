"""Shared by the batch tests: where the build is, tiny models, a fake tool."""
import os
import shutil
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(os.path.dirname(HERE))
BUILD_DIR = os.environ.get("MR_BUILD_DIR", os.path.join(SOURCE_DIR, "build"))
TOOLS_DIR = os.environ.get("MR_TOOLS_DIR", os.path.join(BUILD_DIR, "tools"))
BATCH = os.environ.get("MR_BATCH", os.path.join(BUILD_DIR, "tools", "meshrepair-batch", "meshrepair-batch"))
EXAMPLES = os.path.join(SOURCE_DIR, "examples")
PACKAGE_DIR = os.path.join(SOURCE_DIR, "tools", "meshrepair-batch")


def tool(name):
    return os.path.join(TOOLS_DIR, name, name)


def have_dask():
    try:
        import distributed  # noqa: F401
        return True
    except ImportError:
        return False


def run_batch(args, timeout=120, env=None):
    """Runs meshrepair-batch to completion; CompletedProcess with text output."""
    env = dict(os.environ if env is None else env, MR_TOOLS_DIR=TOOLS_DIR)
    return subprocess.run([BATCH] + list(args), capture_output=True, text=True, timeout=timeout, env=env,
                          check=False)


def cube(path, size=1.0, offset=(0.0, 0.0, 0.0)):
    """A closed cube as OBJ."""
    v = [(offset[0] + size * (i & 1), offset[1] + size * (i >> 1 & 1), offset[2] + size * (i >> 2 & 1))
         for i in range(8)]
    f = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
         (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]
    with open(path, "w", encoding="ascii") as out:
        out.writelines("v %g %g %g\n" % p for p in v)
        out.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in f)


def open_tetrahedron_off(path):
    """A tetrahedron missing one face, as OFF."""
    with open(path, "w", encoding="ascii") as out:
        out.write("OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n")


def broken_stl(path):
    """A file no reader accepts: 120 bytes of a binary STL that claims 1000 triangles."""
    with open(path, "wb") as out:
        out.write(b"broken".ljust(80, b" ") + struct.pack("<I", 1000) + b"\0" * 36)


def copy_examples(dest):
    """examples/models/*.* into dest."""
    os.makedirs(dest, exist_ok=True)
    for name in os.listdir(os.path.join(EXAMPLES, "models")):
        shutil.copy(os.path.join(EXAMPLES, "models", name), dest)


FAKE_TOOL = r"""#!/bin/sh
# A stand-in for a tool: IN OUT [options] [--stats FILE]. Behaviour by the input's name:
# *broken* fails, *hang* sleeps for a minute, *slow* sleeps a little; else it copies IN to OUT.
in="$1"; out="$2"; shift 2; stats=""
while [ $# -gt 0 ]; do
  case "$1" in --stats) stats="$2"; shift ;; esac
  shift
done
echo $$ > "$in.pid"
case "$(basename "$in")" in
  *broken*) echo "fake: error: $in: cannot read" >&2; exit 2 ;;
  *hang*) exec sleep 60 ;;
  *slow*) sleep "${FAKE_SLOW_S:-0.6}" ;;
esac
[ -n "$stats" ] && printf '{"faces": 12, "fake": true}\n' > "$stats"
cp "$in" "$out.part$$" && mv "$out.part$$" "$out"
"""


def fake_tool(folder):
    """Writes the fake tool into folder and returns its path."""
    path = os.path.join(folder, "fake-tool")
    with open(path, "w", encoding="ascii") as f:
        f.write(FAKE_TOOL)
    os.chmod(path, 0o755)
    return path


def python():
    return sys.executable
