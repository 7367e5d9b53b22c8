"""Tests of run_corpus.py's command line: path arguments made absolute at parse time (a relative
--build-dir once left mesh-check unrunnable from the tools' work folders, every result 'unchecked'),
a missing mesh-check refused at start, and --out-format. The end-to-end case needs mesh-check
(MR_BUILD_DIR, set by ctest, or build/ of the repository).
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

BENCH = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, BENCH)

from corpus import cli, tools  # noqa: E402

RUNNER = os.path.join(BENCH, "run_corpus.py")
BUILD = os.path.abspath(os.environ.get("MR_BUILD_DIR", os.path.join(os.path.dirname(BENCH), "build")))
MESH_CHECK = os.path.join(BUILD, "tools", "mesh-check", "mesh-check")

CUBE_OBJ = ("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
            "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\n"
            "f 2 4 8\nf 2 8 6\n")
# A fake meshrepair: copies its OBJ input to the output path it is given (the cube is watertight).
FAKE_REPAIR = "#!/bin/sh\ncp \"$1\" \"$2\"\n"


class ParseArgs(unittest.TestCase):
    def test_every_path_argument_is_absolute(self):
        cwd = os.getcwd()
        args = cli.parse_args(["--tool", "meshrepair", "--build-dir", "build", "--out", "o", "--corpus", "c",
                               "--tool-path", "mesh-check=bin/mc", "--tool-path", "admesh=/opt/admesh"])
        self.assertEqual(args.build_dir, os.path.join(cwd, "build"))
        self.assertEqual(args.out, os.path.join(cwd, "o"))
        self.assertEqual(args.corpus, os.path.join(cwd, "c"))
        self.assertEqual(args.tool_path, [f"mesh-check={os.path.join(cwd, 'bin', 'mc')}", "admesh=/opt/admesh"])

    def test_out_format(self):
        self.assertEqual(cli.parse_args(["--tool", "meshrepair"]).out_formats, ["glb"])
        self.assertEqual(cli.parse_args(["--tool", "meshrepair", "--out-format", "all"]).out_formats,
                         ["glb", "stl", "drc"])
        self.assertEqual(cli.parse_args(["--tool", "meshrepair", "--out-format", "stl,drc"]).out_formats,
                         ["stl", "drc"])
        self.assertEqual(cli.parse_args(["--tool", "tetrahedralize"]).out_formats, [])
        for bad in (["--tool", "meshrepair", "--out-format", "ply"], ["--tool", "tetrahedralize", "--out-format", "glb"]):
            with self.assertRaises(SystemExit), open(os.devnull, "w") as null:
                stderr, sys.stderr = sys.stderr, null
                try:
                    cli.parse_args(bad)
                finally:
                    sys.stderr = stderr

    def test_one_tool_per_format_sharing_one_executable(self):
        base = tools.all_tools()["meshrepair"]
        stl = tools.with_out_format(base, "stl")
        self.assertEqual((stl.name, stl.program_name, stl.output_name, stl.out_format),
                         ("meshrepair.stl", "meshrepair", "out.stl", "stl"))
        self.assertIn("out.stl", stl.command("in.obj", "/w", 1e-3)[2])
        with tempfile.TemporaryDirectory() as tmp:
            fake = os.path.join(tmp, "repair")
            with open(fake, "w") as f:
                f.write(FAKE_REPAIR)
            os.chmod(fake, 0o755)
            self.assertEqual(tools.locate(stl, "/nowhere", {"meshrepair": fake}).executable, fake)


class MissingMeshCheck(unittest.TestCase):
    def test_refused_at_start(self):
        with tempfile.TemporaryDirectory() as tmp:
            os.makedirs(os.path.join(tmp, "corpus"))
            with open(os.path.join(tmp, "corpus", "cube.obj"), "w") as f:
                f.write(CUBE_OBJ)
            run = subprocess.run([sys.executable, RUNNER, "--tool", "meshrepair", "--corpus", "corpus", "--out", "out",
                                  "--build-dir", "empty-build", "--peers", "none"],
                                 cwd=tmp, capture_output=True, text=True, timeout=60)
            self.assertNotEqual(run.returncode, 0)
            self.assertIn("mesh-check is not built in " + os.path.join(tmp, "empty-build"), run.stderr)
            self.assertFalse(os.path.exists(os.path.join(tmp, "out", "results.jsonl")))


@unittest.skipUnless(os.access(MESH_CHECK, os.X_OK), f"mesh-check not built at {MESH_CHECK}")
class RelativeBuildDir(unittest.TestCase):
    def test_outputs_are_checked(self):
        with tempfile.TemporaryDirectory() as tmp:
            os.makedirs(os.path.join(tmp, "corpus"))
            with open(os.path.join(tmp, "corpus", "cube.obj"), "w") as f:
                f.write(CUBE_OBJ)
            fake = os.path.join(tmp, "fake-meshrepair")
            with open(fake, "w") as f:
                f.write(FAKE_REPAIR)
            os.chmod(fake, 0o755)
            run = subprocess.run([sys.executable, RUNNER, "--tool", "meshrepair", "--corpus", "corpus", "--out", "out",
                                  "--build-dir", os.path.relpath(BUILD, tmp), "--peers", "none",
                                  "--tool-path", "meshrepair=fake-meshrepair", "--out-format", "obj",
                                  "--time-limit", "30"],
                                 cwd=tmp, capture_output=True, text=True, timeout=120)
            self.assertEqual(run.returncode, 0, run.stderr + run.stdout)
            with open(os.path.join(tmp, "out", "results.jsonl")) as f:
                row = json.loads(f.readline())
            self.assertEqual((row["tool"], row["out_format"], row["check"], row["status"]),
                             ("meshrepair.obj", "obj", "passed", "ok"), row)
            self.assertTrue(row["watertight"])
            with open(os.path.join(tmp, "out", "report.md")) as f:
                self.assertIn("| **meshrepair.obj** (ours) | obj | 1/1 (100%) |", f.read())


if __name__ == "__main__":
    unittest.main()
