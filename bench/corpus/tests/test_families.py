"""Tests of bench/make_families.py: each family's defects, byte-for-byte determinism, the manifest the
runner reads. The pieces need numpy (skipped without it); reading goes through a fake format-convert
(a copy of the OBJ), so no build is needed. The last test runs the real format-convert, meshrepair
and mesh-check through run_corpus.py when they are built (MR_BUILD_DIR, set by ctest, or build/).
"""
import csv
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

BENCH = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, BENCH)

from corpus import models  # noqa: E402

try:
    import numpy as np
    import make_families as mf
except ImportError:
    np = mf = None

GENERATOR = os.path.join(BENCH, "make_families.py")
RUNNER = os.path.join(BENCH, "run_corpus.py")
BUILD = os.path.abspath(os.environ.get("MR_BUILD_DIR", os.path.join(os.path.dirname(BENCH), "build")))
TOOLS = {n: os.path.join(BUILD, "tools", n, n) for n in ("format-convert", "mesh-check", "meshrepair")}

CUBE_V = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 2)]
CUBE_F = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
          (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
FAKE_CONVERT = "#!/bin/sh\ncp \"$1\" \"$2\"\n"


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        f.writelines(f"v {x} {y} {z}\n" for x, y, z in vertices)
        f.writelines("f " + " ".join(str(i + 1) for i in face) + "\n" for face in faces)


def write_corpus(folder):
    """cube.obj (closed), sub/open.obj (closed == 0, must be skipped), MANIFEST.tsv."""
    os.makedirs(os.path.join(folder, "sub"))
    write_obj(os.path.join(folder, "cube.obj"), CUBE_V, CUBE_F)
    write_obj(os.path.join(folder, "sub", "open.obj"), CUBE_V, CUBE_F[:-1])
    with open(os.path.join(folder, "MANIFEST.tsv"), "w") as f:
        f.write("file\tfaces\tclosed\ttags\ncube.obj\t12\t1\tclean-closed\nsub/open.obj\t11\t0\topen\n")


def canonical(triangle):
    """A triangle's corners rotated to start at the smallest corner (orientation kept)."""
    rows = [tuple(map(float, c)) for c in triangle]
    i = rows.index(min(rows))
    return tuple(rows[i:] + rows[:i])


def read_binary_stl(path):
    with open(path, "rb") as f:
        data = f.read()
    count = struct.unpack_from("<I", data, 80)[0]
    corners = [struct.unpack_from("<9f", data, 84 + 50 * i + 12) for i in range(count)]
    return data[:80], np.array(corners, dtype=np.float64).reshape(-1, 3, 3)


@unittest.skipIf(mf is None, "numpy missing")
class Families(unittest.TestCase):
    def setUp(self):
        self.vertices = np.array(CUBE_V, dtype=np.float64)
        self.triangles = np.array(CUBE_F, dtype=np.int64)
        self.original = {canonical(t) for t in mf.corners_of(self.vertices, self.triangles)}

    def rng(self, family="test"):
        return mf.family_rng(1, "cube.obj", family)

    def test_parse_obj_fans_polygons_and_reads_every_index_form(self):
        vertices, triangles = mf.parse_obj("# c\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                           "f 1/1/1 2//1 3 4\nf -4 -2 -1\n")
        self.assertEqual(vertices.shape, (4, 3))
        self.assertEqual(triangles.tolist(), [[0, 1, 2], [0, 2, 3], [0, 2, 3]])

    def test_weld_merges_identical_positions_in_first_use_order(self):
        vertices = np.array([[5, 5, 5], [1, 0, 0], [0, 0, 0], [0, 1, 0], [0, 0, 0]], dtype=np.float64)
        welded, triangles = mf.weld(vertices, np.array([[2, 1, 3], [4, 3, 1]]))
        self.assertEqual(welded.tolist(), [[0, 0, 0], [1, 0, 0], [0, 1, 0]])  # unreferenced [5,5,5] gone
        self.assertEqual(triangles.tolist(), [[0, 1, 2], [0, 2, 1]])

    def test_soup_keeps_every_triangle_and_its_orientation(self):
        corners = mf.soup(self.vertices, self.triangles, self.rng())
        self.assertEqual(corners.shape, (12, 3, 3))
        self.assertEqual({canonical(t) for t in corners}, self.original)
        self.assertFalse(np.array_equal(corners, mf.corners_of(self.vertices, self.triangles)), "not shuffled")

    def test_soup_dup_flip_duplicates_ten_and_flips_five_percent(self):
        big_v, big_f = self.grid_sphere()
        original = {canonical(t) for t in mf.corners_of(big_v, big_f)}
        corners = mf.soup_dup_flip(big_v, big_f, self.rng())
        count = len(big_f)
        self.assertEqual(len(corners), count + round(0.10 * count))
        kept = [canonical(t) in original for t in corners]
        flipped = [canonical(t[::-1]) in original for t in corners]
        self.assertTrue(all(k != f for k, f in zip(kept, flipped)), "every triangle is an original or its flip")
        distinct_flipped = {canonical(t) for t, f in zip(corners, flipped) if f}
        self.assertEqual(len(distinct_flipped), round(0.05 * count))
        self.assertEqual(len({canonical(t) for t in corners}), count)

    def grid_sphere(self):
        """A closed octahedron refined twice: 128 triangles."""
        vertices = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
        faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
        for _ in range(2):
            vertices, faces = self.subdivide(vertices, faces)
        return np.array(vertices, dtype=np.float64), np.array(faces, dtype=np.int64)

    @staticmethod
    def subdivide(vertices, faces):
        vertices, middle, result = list(vertices), {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                middle[key] = len(vertices)
                vertices.append(tuple((p + q) / 2 for p, q in zip(vertices[a], vertices[b])))
            return middle[key]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            result += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        return vertices, result

    def test_jitter_moves_every_vertex_by_half_epsilon(self):
        moved, triangles = mf.jitter(self.vertices, self.triangles, self.rng())
        expected = 0.5 * 1e-3 * np.sqrt(6.0)  # bbox 1 x 1 x 2
        lengths = np.linalg.norm(moved - self.vertices, axis=1)
        np.testing.assert_allclose(lengths, expected, rtol=1e-9)
        self.assertEqual(triangles.tolist(), self.triangles.tolist())

    def test_overlap_adds_a_copy_moved_by_a_third_of_the_diagonal(self):
        vertices, triangles = mf.overlap(self.vertices, self.triangles)
        self.assertEqual(len(vertices), 16)
        np.testing.assert_allclose(vertices[8:] - vertices[:8], np.tile([1 / 3, 1 / 3, 2 / 3], (8, 1)), rtol=1e-12)
        self.assertEqual(triangles[12:].tolist(), (self.triangles + 8).tolist())

    def test_graze_adds_a_nearly_coincident_turned_copy(self):
        vertices, triangles = mf.graze(self.vertices, self.triangles, self.rng())
        original, copy = vertices[:8], vertices[8:]
        self.assertEqual(triangles[12:].tolist(), (self.triangles + 8).tolist())
        # A rigid motion: every distance between corners kept.
        pairwise = lambda v: np.linalg.norm(v[:, None, :] - v[None, :, :], axis=2)  # noqa: E731
        np.testing.assert_allclose(pairwise(copy), pairwise(original), atol=1e-12)
        # Each corner moved by at most the turn at its distance from the centre plus the shift, and the
        # centre by the shift alone (half an epsilon of the 1 x 1 x 2 box's diagonal).
        shift = 0.5 * 1e-3 * np.sqrt(6.0)
        centre = np.array([0.5, 0.5, 1.0])
        radius = np.linalg.norm(original - centre, axis=1)
        moved = np.linalg.norm(copy - original, axis=1)
        self.assertTrue(np.all(moved <= mf.GRAZE_ANGLE * radius + shift + 1e-12))
        self.assertTrue(np.all(moved > 0))
        self.assertAlmostEqual(float(np.linalg.norm(copy.mean(axis=0) - centre)), shift, places=12)

    def test_binary_stl_round_trips_the_float32_corners(self):
        corners = mf.soup(self.vertices, self.triangles, self.rng())
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "s.stl")
            mf.write_binary_stl(path, corners, "solid-looking header")
            self.assertEqual(os.path.getsize(path), 84 + 50 * 12)
            header, read = read_binary_stl(path)
        self.assertFalse(header.startswith(b"solid"))
        np.testing.assert_array_equal(read, corners.astype(np.float32))

    def test_boundary_edges(self):
        self.assertEqual(mf.boundary_edges(self.triangles), 0)
        self.assertEqual(mf.boundary_edges(self.triangles[:-1]), 3)
        with_needle = np.concatenate([self.triangles, [[0, 1, 1]]])  # repeated corner: no new boundary
        self.assertEqual(mf.boundary_edges(with_needle), 0)

    def test_select_by_glob_and_size(self):
        rows = [{"file": "a/x.obj", "faces": "10"}, {"file": "b/y.stl", "faces": "5000"}]
        self.assertEqual([r["file"] for r in mf.select(rows, ["a/*"], None)], ["a/x.obj"])
        self.assertEqual([r["file"] for r in mf.select(rows, ["b__y"], None)], ["b/y.stl"])
        self.assertEqual([r["file"] for r in mf.select(rows, [], 2000)], ["a/x.obj"])


@unittest.skipIf(mf is None, "numpy missing")
class Generate(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="families-test-")
        self.corpus = os.path.join(self.tmp, "corpus")
        write_corpus(self.corpus)
        self.convert = os.path.join(self.tmp, "fake-format-convert")
        with open(self.convert, "w") as f:
            f.write(FAKE_CONVERT)
        os.chmod(self.convert, 0o755)

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def generate(self, name, seed=1, families=mf.DEFAULT_FAMILIES if mf else ()):
        out = os.path.join(self.tmp, name)
        mf.generate(self.corpus, out, families, seed, self.convert, log=lambda *a: None)
        return out

    @staticmethod
    def contents(folder):
        result = {}
        for root, _, files in os.walk(folder):
            for name in files:
                with open(os.path.join(root, name), "rb") as f:
                    result[os.path.relpath(os.path.join(root, name), folder)] = f.read()
        return result

    def test_closed_models_only_with_the_corpus_layout(self):
        out = self.generate("a")
        self.assertEqual(sorted(self.contents(out)), ["MANIFEST.tsv", "cube.jitter.obj", "cube.overlap.obj",
                                                      "cube.soup.stl", "cube.soup_dup_flip.stl"])

    def test_graze_only_when_asked_for(self):
        out = self.generate("g", families=("graze",))
        self.assertEqual(sorted(self.contents(out)), ["MANIFEST.tsv", "cube.graze.obj"])
        with open(os.path.join(out, "MANIFEST.tsv"), newline="") as f:
            rows = {r["file"]: r for r in csv.DictReader(f, delimiter="\t")}
        self.assertEqual(rows["cube.graze.obj"]["faces"], "24")
        self.assertIn("near-coincident", rows["cube.graze.obj"]["tags"])

    def test_same_seed_same_bytes_other_seed_other_bytes(self):
        first, again, other = self.generate("a"), self.generate("b"), self.generate("c", seed=2)
        self.assertEqual(self.contents(first), self.contents(again))
        differ = [k for k, v in self.contents(first).items() if self.contents(other)[k] != v]
        self.assertIn("cube.soup.stl", differ)
        self.assertIn("cube.jitter.obj", differ)

    def test_manifest_is_read_by_the_runner(self):
        out = self.generate("a", families=("soup", "overlap"))
        with open(os.path.join(out, "MANIFEST.tsv"), newline="") as f:
            rows = {r["file"]: r for r in csv.DictReader(f, delimiter="\t")}
        self.assertEqual(rows["cube.soup.stl"]["faces"], "12")
        self.assertEqual(rows["cube.soup.stl"]["closed"], "1")
        self.assertEqual(rows["cube.overlap.obj"]["faces"], "24")
        found = {m.key: m for m in models.discover(out)}
        self.assertEqual(sorted(found), ["cube.overlap", "cube.soup"])
        self.assertEqual(found["cube.soup"].faces, 12)
        self.assertIn("soup", found["cube.soup"].tags)


@unittest.skipUnless(all(os.access(p, os.X_OK) for p in TOOLS.values()), f"our tools not built in {BUILD}")
class FamiliesThroughTheRunner(unittest.TestCase):
    def test_meshrepair_on_the_families_in_two_formats(self):
        with tempfile.TemporaryDirectory(prefix="families-run-") as tmp:
            corpus, families, out = (os.path.join(tmp, n) for n in ("corpus", "families", "out"))
            write_corpus(corpus)
            made = subprocess.run([sys.executable, GENERATOR, "--corpus", corpus, "--out", families,
                                   "--build-dir", BUILD], capture_output=True, text=True, timeout=120)
            self.assertEqual(made.returncode, 0, made.stderr)
            run = subprocess.run([sys.executable, RUNNER, "--tool", "meshrepair", "--corpus", families, "--out", out,
                                  "--build-dir", BUILD, "--peers", "none", "--out-format", "glb,stl",
                                  "--time-limit", "60", "--models", "*soup*"],
                                 capture_output=True, text=True, timeout=300)
            self.assertEqual(run.returncode, 0, run.stderr + run.stdout)
            with open(os.path.join(out, "results.jsonl")) as f:
                rows = [json.loads(line) for line in f]
            self.assertEqual(sorted((r["model"], r["tool"], r["out_format"]) for r in rows), [
                ("cube.soup", "meshrepair.glb", "glb"), ("cube.soup", "meshrepair.stl", "stl"),
                ("cube.soup_dup_flip", "meshrepair.glb", "glb"), ("cube.soup_dup_flip", "meshrepair.stl", "stl")])
            for r in rows:
                self.assertTrue(r["output"].endswith("out." + r["out_format"]), r)
                self.assertNotEqual(r["status"], "unchecked", r)


if __name__ == "__main__":
    unittest.main()
