"""The optional fTetWild peer of run_corpus.py (--peers ftetwild), with a fake FloatTetwild_bin (< 30 s).

The fake writes what the real one writes: a binary MSH 2.2 file exactly as fTetWild's MshSaver lays it out
(no newline after the endianness int, a per-tet "color" $ElementData section), plus its side files named
after -o (out.msh__sf.obj, out.msh__tracked_surface.stl, out.msh_.csv). It tetrahedralizes the cube, fails
on the tetrahedron as fTetWild does on a file it cannot load, and refuses to run unless given
--max-threads 1. Checked: the command line,
mesh-check reading the binary output and judging it like ours, side files in the run's folder and none
beside the input, the report's rows, and "not available" when FloatTetwild_bin is neither given nor on PATH.
Needs mesh-check: MR_BUILD_DIR (set by ctest) or build/ of the repository.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import types
import unittest

BENCH = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, BENCH)

from corpus import runner, tools  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_fake_tool import FAKE_TOOL, UNIT_CUBE_TETS, read_rows, write_corpus  # noqa: E402

RUNNER = os.path.join(BENCH, "run_corpus.py")
BUILD = os.environ.get("MR_BUILD_DIR", os.path.join(os.path.dirname(BENCH), "build"))
MESH_CHECK = os.path.join(BUILD, "tools", "mesh-check", "mesh-check")

FAKE_FTETWILD = r'''
import json, os, struct, sys
args = sys.argv[1:]
def value(flag):
    return args[args.index(flag) + 1] if flag in args else None
if value("--max-threads") != "1":
    sys.exit("fake FloatTetwild_bin: expected --max-threads 1, got " + " ".join(args))
inp, out = value("-i"), value("-o")
if os.path.basename(inp).startswith("tet"):
    print("[error] Unable to load mesh at " + inp)
    sys.exit(1)
''' + UNIT_CUBE_TETS + r'''with open(out, "wb") as f:
    f.write(b"$MeshFormat\n2.2 1 8\n" + struct.pack("<i", 1) + b"$EndMeshFormat\n")
    f.write(b"$Nodes\n%d\n" % len(pts))
    for i, p in enumerate(pts):
        f.write(struct.pack("<i3d", i + 1, *p))
    f.write(b"$EndNodes\n$Elements\n%d\n" % len(tets) + struct.pack("<3i", 4, len(tets), 0))
    for i, t in enumerate(map(orient, tets)):
        f.write(struct.pack("<5i", i + 1, *(j + 1 for j in t)))
    f.write(b"$EndElements\n$ElementData\n1\n\"color\"\n1\n0.0\n3\n0\n1\n%d\n" % len(tets))
    for i in range(len(tets)):
        f.write(struct.pack("<id", i + 1, 3.0))
    f.write(b"$EndElementData\n")
for side in ("__sf.obj", "__tracked_surface.stl"):
    with open(out + side, "w") as f:
        f.write("solid\nendsolid\n" if side.endswith(".stl") else "v 0 0 0\n")
with open(out + "_.csv", "w") as f:
    json.dump(sys.argv, f)
'''


def _executable(path, body):
    with open(path, "w") as f:
        f.write(f"#!{sys.executable}\n{body}")
    os.chmod(path, 0o755)
    return path


def _files_under(folder):
    return sorted(os.path.relpath(os.path.join(d, n), folder) for d, _, names in os.walk(folder) for n in names)


@unittest.skipUnless(os.access(MESH_CHECK, os.X_OK) or "MR_BUILD_DIR" in os.environ,
                     f"mesh-check not built at {MESH_CHECK}")
class FTetWildPeer(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="bench-ftetwild-test-")
        cls.corpus = os.path.join(cls.tmp, "corpus")
        os.makedirs(cls.corpus)
        write_corpus(cls.corpus)
        cls.corpus_files = _files_under(cls.corpus)
        cls.ours = _executable(os.path.join(cls.tmp, "fake_tetrahedralize"), FAKE_TOOL)
        cls.ftetwild = _executable(os.path.join(cls.tmp, "FloatTetwild_bin"), FAKE_FTETWILD)
        cls.out = os.path.join(cls.tmp, "out")
        cls.result = cls.run_corpus(cls.out, "--peers", "ftetwild", "--tool-path", f"ftetwild={cls.ftetwild}")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    @classmethod
    def run_corpus(cls, out, *extra, env=None):
        command = [sys.executable, RUNNER, "--tool", "tetrahedralize", "--corpus", cls.corpus, "--out", out,
                   "--build-dir", BUILD, "--tool-path", f"tetrahedralize={cls.ours}", "--models", "cube*",
                   "--models", "tet*", "--time-limit", "20", "--check-time-limit", "60", *extra]
        return subprocess.run(command, capture_output=True, text=True, timeout=120, env=env)

    def rows(self):
        return {(r["model"], r["tool"]): r for r in read_rows(self.out)}

    def test_run_succeeds(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr + self.result.stdout)

    def test_command_line(self):
        with open(os.path.join(self.out, "models", "cube", "ftetwild", "out.msh_.csv")) as f:
            argv = json.load(f)
        workdir = os.path.join(self.out, "models", "cube", "ftetwild")
        self.assertEqual(argv[1:], ["-i", os.path.join(self.corpus, "cube.obj"), "-o",
                                    os.path.join(workdir, "out.msh"), "-e", "0.001", "--max-threads", "1"])

    def test_binary_msh_is_judged_like_ours(self):
        rows = self.rows()
        ours, peer = rows[("cube", "tetrahedralize")], rows[("cube", "ftetwild")]
        self.assertEqual(peer["status"], "ok", peer)
        self.assertEqual((peer["ours"], peer["task"], peer["out_format"], peer["check"]),
                         (False, "tetrahedralize", "msh", "passed"))
        self.assertEqual(peer["output"], os.path.join("models", "cube", "ftetwild", "out.msh"))
        for key in ("out_tets", "out_vertices", "inverted_tets", "degenerate_tets", "closed", "within_envelope",
                    "min_dihedral_deg", "max_amips", "avg_amips"):
            self.assertEqual(peer[key], ours[key], key)
        self.assertAlmostEqual(peer["out_volume"], 1.0, places=9)
        self.assertIsNone(peer["tool_stats"])
        self.assertGreater(peer["cpu_s"], 0)

    def test_failure_is_classified(self):
        row = self.rows()[("tet", "ftetwild")]
        self.assertEqual(row["status"], "error", row)
        self.assertIn("Unable to load mesh", row["note"])

    def test_side_files_land_in_the_run_folder(self):
        self.assertEqual(_files_under(self.corpus), self.corpus_files)
        workdir = os.path.join(self.out, "models", "cube", "ftetwild")
        for name in ("out.msh", "out.msh__sf.obj", "out.msh__tracked_surface.stl", "out.msh_.csv",
                     "tool.stdout.txt"):
            self.assertTrue(os.path.isfile(os.path.join(workdir, name)), name)

    def test_report_shows_it_beside_ours(self):
        with open(os.path.join(self.out, "report.md")) as f:
            report = f.read()
        self.assertIn("**tetrahedralize** (ours) 1/2 (50%) valid; ftetwild 1/2 (50%) valid", report)
        self.assertIn("| ftetwild | msh | 1/2 (50%) |", report)
        self.assertRegex(report, r"\| tetrahedralize \| ftetwild \|")  # time ratios and per-model columns
        self.assertRegex(report, r"\n\| ftetwild \| 1 \| ")  # quality table
        self.assertIn("- **ftetwild**: `FloatTetwild_bin -i IN -o out.msh -e EPS --max-threads 1`", report)
        self.assertIn(f"`{self.ftetwild}`", report)

    def test_not_available_without_a_path(self):
        path = os.pathsep.join(p for p in ("/usr/bin", "/bin") if os.path.isdir(p))
        if shutil.which("FloatTetwild_bin", path=path):
            self.skipTest("FloatTetwild_bin is installed on the system PATH")
        out = os.path.join(self.tmp, "missing")
        run = self.run_corpus(out, "--peers", "ftetwild", env=dict(os.environ, PATH=path))
        self.assertEqual(run.returncode, 0, run.stderr + run.stdout)
        self.assertIn("ftetwild: not available (not installed (no `FloatTetwild_bin` on PATH); build it from the "
                      "public wildmeshing/fTetWild repository", run.stdout)
        self.assertEqual({r["tool"] for r in read_rows(out)}, {"tetrahedralize"})
        with open(os.path.join(out, "report.md")) as f:
            self.assertIn("| ftetwild | msh | not available: not installed", f.read())

    def test_wrong_path_is_named(self):
        tool = tools.locate(tools.all_tools()["ftetwild"], BUILD, {"ftetwild": "/nowhere/FloatTetwild_bin"})
        self.assertFalse(tool.available)
        self.assertTrue(tool.unavailable.startswith("no executable at /nowhere/FloatTetwild_bin; build it"))


class FTetWildPieces(unittest.TestCase):
    def test_not_a_default_peer(self):
        self.assertIn("ftetwild", tools.all_tools())
        self.assertNotIn("ftetwild", tools.DEFAULT_PEERS["tetrahedralize"])

    def test_reads_its_formats_as_they_are_and_others_converted(self):
        tool = tools.all_tools()["ftetwild"]
        ctx = types.SimpleNamespace(format_convert=None)
        with tempfile.TemporaryDirectory() as tmp:
            for name in ("a.obj", "b.STL", "c.off", "d.ply"):
                model = types.SimpleNamespace(path=os.path.join("/corpus", name))
                self.assertEqual(runner.prepare_input(ctx, tool, model, tmp), (model.path, ""))
            glb = types.SimpleNamespace(path="/corpus/e.glb")
            self.assertEqual(runner.prepare_input(ctx, tool, glb, tmp), (None, "format-convert not built"))


if __name__ == "__main__":
    unittest.main()
