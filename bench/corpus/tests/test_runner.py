"""End-to-end test of the corpus runner on a tiny generated folder (no manifest).

Needs the built tools: MR_BUILD_DIR (set by ctest) or build/ next to the repository.
"""
import json
import os
import struct
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
RUNNER = os.path.join(HERE, "..", "..", "run_corpus.py")
BUILD = os.environ.get("MR_BUILD_DIR", os.path.join(HERE, "..", "..", "..", "build"))


def write_cube_stl(path, size):
    corners = [(x, y, z) for z in (0, size) for y in (0, size) for x in (0, size)]
    faces = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
             (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]
    with open(path, "wb") as out:
        out.write(b"cube".ljust(80, b" ") + struct.pack("<I", len(faces)))
        for f in faces:
            out.write(struct.pack("<3f", 0, 0, 0))
            for i in f:
                out.write(struct.pack("<3f", *corners[i]))
            out.write(b"\0\0")


def write_open_grid_obj(path, n):
    lines = ["v %d %d 0" % (i, j) for j in range(n + 1) for i in range(n + 1)]
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            lines += ["f %d %d %d" % (a, a + 1, a + n + 2), "f %d %d %d" % (a, a + n + 2, a + n + 1)]
    with open(path, "w") as out:
        out.write("\n".join(lines) + "\n")


def run(*args):
    return subprocess.run([sys.executable, RUNNER, "--build-dir", BUILD] + list(args),
                          capture_output=True, text=True, timeout=300)


def results(out):
    with open(os.path.join(out, "results.jsonl")) as f:
        return [json.loads(line) for line in f if line.strip()]


class RunnerTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.corpus = os.path.join(self.dir.name, "models")
        os.makedirs(os.path.join(self.corpus, "sub"))
        write_cube_stl(os.path.join(self.corpus, "cube.stl"), 2.0)
        write_open_grid_obj(os.path.join(self.corpus, "sub", "grid.obj"), 12)
        with open(os.path.join(self.corpus, "broken.off"), "w") as f:
            f.write("OFF\n4 1 0\n0 0 0\n1 0 0\n")  # truncated: ours must fail as 'error'

    def tearDown(self):
        self.dir.cleanup()

    def test_ours_checked_and_resumed(self):
        out = os.path.join(self.dir.name, "simplify")
        first = run("--tool", "simplify-in-envelope", "--corpus", self.corpus, "--out", out, "--time-limit", "60")
        self.assertEqual(first.returncode, 0, first.stderr + first.stdout)
        rows = results(out)
        by_model = {r["model"]: r for r in rows}
        self.assertEqual(sorted(by_model), ["broken", "cube", "sub__grid"])
        for key in ("model", "tool", "status", "wall_s", "cpu_s", "peak_mb", "input_faces", "check"):
            self.assertIn(key, rows[0])
        self.assertEqual(by_model["cube"]["status"], "ok")
        self.assertTrue(by_model["cube"]["watertight"])
        self.assertEqual(by_model["sub__grid"]["status"], "ok")
        self.assertLess(by_model["sub__grid"]["out_faces"], 288)
        self.assertEqual(by_model["broken"]["status"], "error")
        with open(os.path.join(out, "report.md")) as f:
            report = f.read()
        self.assertIn("| tool | output checked | valid / attempted |", report)
        self.assertIn("2/3", report)
        self.assertIn("Machine:", report)
        self.assertTrue(os.path.exists(os.path.join(out, "time_vs_size.png")))

        again = run("--tool", "simplify-in-envelope", "--corpus", self.corpus, "--out", out, "--time-limit", "60")
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertEqual(len(results(out)), len(rows), "a resumed run must not redo finished models")

    def test_peer_runs_when_ours_is_missing(self):
        out = os.path.join(self.dir.name, "tet")
        proc = run("--tool", "tetrahedralize", "--peers", "tetgen", "--corpus", self.corpus, "--out", out,
                   "--time-limit", "60", "--models", "cube*", "--tool-path",
                   "tetrahedralize=" + os.path.join(self.dir.name, "does-not-exist"))
        self.assertEqual(proc.returncode, 0, proc.stderr + proc.stdout)
        rows = [r for r in results(out) if r["tool"] == "tetgen"]
        self.assertEqual(len(rows), 1)
        self.assertEqual(rows[0]["status"], "ok")
        self.assertEqual(rows[0]["inverted_tets"], 0)
        with open(os.path.join(out, "report.md")) as f:
            self.assertIn("not available", f.read())


if __name__ == "__main__":
    unittest.main()
