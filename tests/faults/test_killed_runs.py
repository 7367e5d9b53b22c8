#!/usr/bin/python3
"""Runs killed at random moments, or out of room for their output, leave the previous output
or none, never a partial file.

Each tool run is first done in full (its bytes are the reference: the tools are
deterministic), then started again and again and stopped by SIGKILL, SIGTERM or
SIGINT after a random delay up to the full run's time. After every stop the output
folder must hold exactly the previous output (or nothing, if there was none) or the
complete new one, and no other file (but the complete new output under a hidden name,
which SIGKILL can leave between the two calls that replace a file); SIGTERM and SIGINT must end the run within a
second. MR_FAULT_KILLS (default 100) sets the number of stops, MR_FAULT_SEED the seed.
A full disk is played by RLIMIT_FSIZE: writing past it fails with EFBIG (SIGXFSZ ignored)
or ends the process by SIGXFSZ (its default).
"""
import os
import pathlib
import random
import resource
import signal
import struct
import subprocess
import tempfile
import time
import unittest

BUILD = pathlib.Path(os.environ.get("MR_BUILD_DIR", "build")).resolve()
EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "models"
KILLS = int(os.environ.get("MR_FAULT_KILLS", "100"))
SEED = int(os.environ.get("MR_FAULT_SEED", "1"))
PROMPT_STOP_SECONDS = 1.0


def tool(name):
    return str(BUILD / "tools" / name / name)


def write_large_soup_stl(path, rings=300, segments=400):
    """A closed sphere as a binary STL soup, large enough that writing it takes a while."""
    import math
    triangles = []
    def point(i, j):
        theta, phi = math.pi * i / rings, 2 * math.pi * j / segments
        return (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))
    for i in range(rings):
        for j in range(segments):
            a, b, c, d = point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)
            if i > 0:
                triangles.append((a, b, d))
            if i < rings - 1:
                triangles.append((b, c, d))
    with open(path, "wb") as out:
        out.write(b"killed-run test soup".ljust(80, b" "))
        out.write(struct.pack("<I", len(triangles)))
        for t in triangles:
            out.write(struct.pack("<12fH", 0, 0, 0, *t[0], *t[1], *t[2], 0))


class KilledRuns(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory(prefix="mr_killed_runs_")
        root = pathlib.Path(cls.folder.name)
        cls.inputs = root / "in"
        cls.inputs.mkdir()
        write_large_soup_stl(cls.inputs / "sphere.stl")
        cls.random = random.Random(SEED)

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def reference_run(self, command, output):
        started = time.monotonic()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        elapsed = time.monotonic() - started
        return output.read_bytes(), elapsed

    def stop_at_random(self, command, output, reference, full_time, previous):
        """One run stopped after a random delay; checks what it left."""
        folder = output.parent
        for leftover in folder.iterdir():
            leftover.unlink()
        if previous:
            output.write_bytes(reference)
        which = self.random.choice([signal.SIGKILL, signal.SIGKILL, signal.SIGTERM, signal.SIGINT])
        delay = self.random.uniform(0.0, 1.1 * full_time)
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(delay)
        signalled = time.monotonic()
        process.send_signal(which)
        process.wait()
        stop_time = time.monotonic() - signalled
        context = f"{which.name} after {delay:.3f} s (seed {SEED}, previous output {previous})"
        if which != signal.SIGKILL and process.returncode < 0:
            self.assertLess(stop_time, PROMPT_STOP_SECONDS, f"slow to stop on {context}")
        names = sorted(p.name for p in folder.iterdir())
        if which == signal.SIGKILL and previous:
            self.forgive_the_rename_window(folder, output, reference, names, context)
        if output.exists():
            self.assertEqual(names, [output.name], f"stray files {names} after {context}")
            self.assertEqual(output.read_bytes(), reference, f"partial or different output after {context}")
        else:
            self.assertFalse(previous, f"previous output lost after {context}")
            self.assertEqual(names, [], f"stray files {names} after {context}")

    def forgive_the_rename_window(self, folder, output, reference, names, context):
        """Replacing a file takes two calls (link the finished output under a hidden name,
        rename it over the old one): no call links a file over another. SIGKILL between
        them leaves the complete new output under that name beside the previous output.
        Only that is forgiven: one hidden sibling holding exactly the full run's bytes."""
        hidden = [n for n in names if n.startswith(f".{output.stem}.tmp") and n.endswith(output.suffix)]
        if len(hidden) != 1 or (folder / hidden[0]).read_bytes() != reference:
            return
        (folder / hidden[0]).unlink()
        names.remove(hidden[0])

    def run_kills(self, command, output, kills):
        output.parent.mkdir(exist_ok=True)
        reference, full_time = self.reference_run(command, output)
        for k in range(kills):
            self.stop_at_random(command, output, reference, full_time, previous=(k % 2 == 1))

    def test_format_convert_killed_while_reading_or_writing(self):
        out = pathlib.Path(self.folder.name) / "convert" / "sphere.obj"
        command = [tool("format-convert"), str(self.inputs / "sphere.stl"), str(out)]
        self.run_kills(command, out, KILLS // 2)

    def test_meshrepair_killed_at_any_stage(self):
        out = pathlib.Path(self.folder.name) / "repair" / "torus.glb"
        command = [tool("meshrepair"), str(EXAMPLES / "torus_soup.ply"), str(out), "-j", "2"]
        self.run_kills(command, out, KILLS - KILLS // 2)

    def test_output_larger_than_the_room_left(self):
        folder = pathlib.Path(self.folder.name) / "full"
        folder.mkdir(exist_ok=True)
        out = folder / "sphere.obj"
        command = [tool("format-convert"), str(self.inputs / "sphere.stl"), str(out)]
        previous = b"the previous output\n"
        for signal_kills in (False, True):
            out.write_bytes(previous)

            def limit_file_size(kill=signal_kills):
                if not kill:
                    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
                resource.setrlimit(resource.RLIMIT_FSIZE, (100_000, 100_000))

            run = subprocess.run(command, preexec_fn=limit_file_size, capture_output=True, text=True)
            if signal_kills:
                self.assertEqual(run.returncode, -signal.SIGXFSZ, run.stderr)
            else:
                self.assertEqual(run.returncode, 1, run.stderr)
                self.assertIn(str(out), run.stderr)
            self.assertEqual(sorted(p.name for p in folder.iterdir()), [out.name])
            self.assertEqual(out.read_bytes(), previous)


if __name__ == "__main__":
    unittest.main()
