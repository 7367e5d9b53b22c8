"""examples/Makefile: `make -j2` over a copy of examples/ builds a repaired GLB, a Draco GLB and a
tet mesh per model, each passing mesh-check; a broken model makes make fail and leaves no target."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import batch_support as bs  # noqa: E402


def make(folder, *targets):
    return subprocess.run(["make", "-j2", f"BIN={bs.TOOLS_DIR}"] + list(targets), cwd=folder, capture_output=True,
                          text=True, timeout=300, check=False)


@unittest.skipUnless(shutil.which("make"), "make is not installed")
class ExamplesMakefile(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="mr_examples_")
        self.examples = os.path.join(self._tmp.name, "examples")
        shutil.copytree(bs.EXAMPLES, self.examples, ignore=shutil.ignore_patterns("out"))

    def tearDown(self):
        self._tmp.cleanup()

    def names(self):
        return sorted(os.path.splitext(n)[0] for n in os.listdir(os.path.join(self.examples, "models")))

    def test_pipeline_then_broken_model(self):
        done = make(self.examples)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        out = os.path.join(self.examples, "out")
        names = self.names()
        self.assertEqual(len(names), 3)
        expected = [f"{n}{suffix}" for n in names for suffix in (".glb", ".draco.glb", ".msh")]
        self.assertEqual(sorted(os.listdir(out)), sorted(expected))
        for name in expected:
            checked = subprocess.run([bs.tool("mesh-check"), os.path.join(out, name), "-q", "-j", "1"], check=False)
            self.assertEqual(checked.returncode, 0, f"mesh-check {name}")
        with open(os.path.join(out, names[0] + ".draco.glb"), "rb") as f:
            self.assertIn(b"KHR_draco_mesh_compression", f.read())
        self.assertIn("Nothing to be done", make(self.examples).stdout)

        bs.broken_stl(os.path.join(self.examples, "models", "broken.stl"))
        failed = make(self.examples, "-k")
        self.assertNotEqual(failed.returncode, 0)
        self.assertIn("broken.stl", failed.stderr)
        self.assertEqual(sorted(os.listdir(out)), sorted(expected))  # no broken.* left, partial or not
        again = make(self.examples)
        self.assertNotEqual(again.returncode, 0)  # still failing: nothing was left to look done
        self.assertFalse(any(n.startswith("broken") for n in os.listdir(out)))


if __name__ == "__main__":
    unittest.main()
