"""End-to-end test of bench/run_corpus.py with a fake tool on a tiny generated corpus (< 30 s).

A fake `tetrahedralize` (a Python script passed with --tool-path) makes a valid tet mesh of the cube,
aborts on the tetrahedron and hangs on the open square, so one run exercises ok, crash and timeout,
the checks by the real mesh-check, resume, --models, --report-only and the report. Needs mesh-check:
MR_BUILD_DIR (set by ctest) or build/ of the repository.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

BENCH = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, BENCH)

from corpus import baseline, check, models, summary  # noqa: E402
from corpus import results  # noqa: E402
from corpus.results import ROW_KEYS  # noqa: E402

RUNNER = os.path.join(BENCH, "run_corpus.py")
BUILD = os.environ.get("MR_BUILD_DIR", os.path.join(os.path.dirname(BENCH), "build"))
MESH_CHECK = os.path.join(BUILD, "tools", "mesh-check", "mesh-check")

CUBE_V = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
CUBE_F = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
          (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]

# The unit cube in five positive tets, as the fake tools write it.
UNIT_CUBE_TETS = r'''
pts = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
tets = [(0, 1, 2, 4), (1, 2, 3, 7), (1, 4, 5, 7), (2, 4, 6, 7), (1, 2, 4, 7)]
def orient(t):
    a, b, c, d = (pts[i] for i in t)
    u, v, w = ([q[k] - a[k] for k in range(3)] for q in (b, c, d))
    det = u[0]*(v[1]*w[2]-v[2]*w[1]) - u[1]*(v[0]*w[2]-v[2]*w[0]) + u[2]*(v[0]*w[1]-v[1]*w[0])
    return t if det > 0 else (t[1], t[0], t[2], t[3])
'''

FAKE_TOOL = r'''
import os, sys, time, json
inp, out = sys.argv[1], sys.argv[2]
name = os.path.basename(inp)
if name.startswith("tet"):
    os.abort()
if name.startswith("open"):
    time.sleep(60)
''' + UNIT_CUBE_TETS + r'''with open(out, "w") as f:
    f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(pts))
    for i, p in enumerate(pts):
        f.write("%d %g %g %g\n" % ((i + 1,) + p))
    f.write("$EndNodes\n$Elements\n%d\n" % len(tets))
    for i, t in enumerate(map(orient, tets)):
        f.write("%d 4 2 1 1 %d %d %d %d\n" % ((i + 1,) + tuple(j + 1 for j in t)))
    f.write("$EndElements\n")
with open(sys.argv[sys.argv.index("--stats") + 1], "w") as f:
    json.dump({"tets": len(tets)}, f)
'''


def write_corpus(folder):
    with open(os.path.join(folder, "cube.obj"), "w") as f:
        f.writelines(f"v {x} {y} {z}\n" for x, y, z in CUBE_V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in CUBE_F)
    tet = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    with open(os.path.join(folder, "tet.stl"), "w") as f:
        f.write("solid t\n")
        for a, b, c in [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]:
            f.write("facet normal 0 0 0\nouter loop\n")
            f.writelines(f"vertex {tet[i][0]} {tet[i][1]} {tet[i][2]}\n" for i in (a, b, c))
            f.write("endloop\nendfacet\n")
        f.write("endsolid t\n")
    os.makedirs(os.path.join(folder, "sub"))
    with open(os.path.join(folder, "sub", "open.off"), "w") as f:
        f.write("OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")


def read_rows(out):
    with open(os.path.join(out, "results.jsonl")) as f:
        return [json.loads(line) for line in f]


@unittest.skipUnless(os.access(MESH_CHECK, os.X_OK) or "MR_BUILD_DIR" in os.environ,
                     f"mesh-check not built at {MESH_CHECK}")
class RunnerEndToEnd(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="bench-runner-test-")
        cls.corpus = os.path.join(cls.tmp, "corpus")
        os.makedirs(cls.corpus)
        write_corpus(cls.corpus)
        cls.fake = os.path.join(cls.tmp, "fake_tetrahedralize")
        with open(cls.fake, "w") as f:
            f.write(f"#!{sys.executable}\n{FAKE_TOOL}")
        os.chmod(cls.fake, 0o755)
        cls.out = os.path.join(cls.tmp, "out")
        cls.first = cls.run_corpus(cls.out)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    @classmethod
    def run_corpus(cls, out, *extra):
        command = [sys.executable, RUNNER, "--tool", "tetrahedralize", "--corpus", cls.corpus, "--out", out,
                   "--build-dir", BUILD, "--tool-path", f"tetrahedralize={cls.fake}", "--peers", "none",
                   "--time-limit", "3", "--check-time-limit", "60", *extra]
        return subprocess.run(command, capture_output=True, text=True, timeout=120)

    def test_first_run_succeeds(self):
        self.assertEqual(self.first.returncode, 0, self.first.stderr + self.first.stdout)

    def test_rows_have_every_key_and_the_right_status(self):
        rows = {r["model"]: r for r in read_rows(self.out)}
        self.assertEqual(set(rows), {"cube", "tet", "sub__open"})
        for row in rows.values():
            self.assertTrue(set(ROW_KEYS + check.CHECK_FIELDS) <= set(row), row)
        self.assertEqual(rows["cube"]["status"], "ok", rows["cube"])
        self.assertEqual(rows["tet"]["status"], "crash", rows["tet"])
        self.assertEqual(rows["tet"]["signal"], 6)
        self.assertEqual(rows["sub__open"]["status"], "timeout", rows["sub__open"])
        self.assertGreaterEqual(rows["sub__open"]["wall_s"], 3.0)

    def test_valid_output_is_measured_by_mesh_check(self):
        cube = {r["model"]: r for r in read_rows(self.out)}["cube"]
        self.assertEqual(cube["out_tets"], 5)
        self.assertEqual(cube["input_faces"], 12)
        self.assertAlmostEqual(cube["out_volume"], 1.0, places=9)
        self.assertTrue(cube["closed"])
        self.assertTrue(cube["within_envelope"])
        self.assertGreater(cube["min_dihedral_deg"], 0)
        self.assertIsNotNone(cube["max_amips"])
        self.assertGreater(cube["peak_mb"], 0)
        self.assertEqual(cube["tool_stats"], {"tets": 5})
        self.assertTrue(os.path.isfile(os.path.join(self.out, "models", "cube", "tetrahedralize", "out.msh")))

    def test_report_has_the_success_table(self):
        with open(os.path.join(self.out, "report.md")) as f:
            report = f.read()
        self.assertIn("## Success", report)
        self.assertIn("| tool | output checked | valid / attempted | crash | timeout |", report)
        self.assertIn("| **tetrahedralize** (ours) | msh | 1/3 (33%) | 1 | 1 |", report)
        self.assertIn("## Run", report)
        self.assertIn("--tool tetrahedralize", report)
        self.assertIn("## Per model", report)

    def test_plots_are_written(self):
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            if not os.access("/usr/bin/python3", os.X_OK):
                self.skipTest("no matplotlib")
        for name in ("time_vs_size.png", "success_by_tag.png", "dihedral.png", "amips.png"):
            self.assertTrue(os.path.getsize(os.path.join(self.out, name)) > 1000, name)

    def test_resume_runs_only_what_is_missing(self):
        out = os.path.join(self.tmp, "resume")
        shutil.copytree(self.out, out)
        path = os.path.join(out, "results.jsonl")
        with open(path) as f:
            lines = f.readlines()
        kept = [ln for ln in lines if '"model": "sub__open"' not in ln]
        with open(path, "w") as f:
            f.writelines(kept + ['{"model": "torn'])  # as if killed while writing
        result = self.run_corpus(out, "--models", "cube*", "--models", "sub/*")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("1 runs to do", result.stdout)
        rows = results.read_rows(path)  # skips the torn line
        self.assertEqual(sorted(r["model"] for r in rows), ["cube", "sub__open", "tet"])
        self.assertEqual(next(r for r in rows if r["model"] == "sub__open")["status"], "timeout")

    def test_models_filter_and_report_only(self):
        out = os.path.join(self.tmp, "filtered")
        result = self.run_corpus(out, "--models", "cube*")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual([r["model"] for r in read_rows(out)], ["cube"])
        os.remove(os.path.join(out, "report.md"))
        again = subprocess.run([sys.executable, RUNNER, "--report-only", "--out", out], capture_output=True,
                               text=True, timeout=60)
        self.assertEqual(again.returncode, 0, again.stderr)
        with open(os.path.join(out, "report.md")) as f:
            self.assertIn("1/1 (100%)", f.read())


class Pieces(unittest.TestCase):
    def test_model_key(self):
        self.assertEqual(models.model_key("c3d/beetle.obj"), "c3d__beetle")
        self.assertEqual(models.model_key("trimesh/counter.unitsmm.STL"), "trimesh__counter.unitsmm")

    def test_manifest_gives_tags_and_faces(self):
        with tempfile.TemporaryDirectory() as folder:
            write_corpus(folder)
            with open(os.path.join(folder, "MANIFEST.tsv"), "w") as f:
                f.write("file\tfaces\ttags\ncube.obj\t12\tclean-closed,tiny(<100f)\n")
            found = models.discover(folder)
            self.assertEqual([(m.key, m.faces, m.tags) for m in found], [("cube", 12, ("clean-closed", "tiny(<100f)"))])
            os.remove(os.path.join(folder, "MANIFEST.tsv"))
            self.assertEqual(sorted(m.key for m in models.discover(folder)), ["cube", "sub__open", "tet"])
            self.assertTrue(all(m.tags == () for m in models.discover(folder)))

    def test_baseline_status_kinds(self):
        self.assertEqual(baseline.status_kind("fail rc 134 (signal 6)"), "crash")
        self.assertEqual(baseline.status_kind("fail rc 1"), "error")
        self.assertEqual(baseline.status_kind("fail (rc 0, empty/no output)"), "empty")
        self.assertEqual(baseline.status_kind("timeout"), "timeout")

    def test_verdicts(self):
        good = {"out_tets": 4, "inverted_tets": 0, "degenerate_tets": 0, "closed": True, "within_envelope": True}
        self.assertEqual(check.verdict("tetrahedralize", "volume", good)[0], "ok")
        self.assertEqual(check.verdict("tetrahedralize", "volume", dict(good, out_tets=0))[0], "empty")
        self.assertEqual(check.verdict("tetrahedralize", "volume", dict(good, inverted_tets=1))[0], "invalid")
        self.assertEqual(check.verdict("tetrahedralize", "volume", dict(good, within_envelope=False))[0], "invalid")
        # an open input's holes are filled: leaving the envelope there is allowed
        self.assertEqual(check.verdict("tetrahedralize", "volume", dict(good, within_envelope=False),
                                       input_closed=False)[0], "ok")
        self.assertFalse(check.input_is_closed(("open", "holes")))
        self.assertTrue(check.input_is_closed(("clean-closed",)))
        self.assertEqual(check.verdict("meshrepair", "surface", {"out_faces": 8, "watertight": False})[0], "invalid")

    def test_paired_ratio(self):
        a = [{"model": "m1", "status": "ok", "cpu_s": 2.0}, {"model": "m2", "status": "crash", "cpu_s": 1.0}]
        b = [{"model": "m1", "status": "ok", "cpu_s": 1.0}, {"model": "m2", "status": "ok", "cpu_s": 1.0}]
        self.assertEqual(summary.paired_ratios(a, b, "cpu_s"), (2.0, 1))


if __name__ == "__main__":
    unittest.main()
