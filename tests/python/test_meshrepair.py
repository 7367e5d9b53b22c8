"""The Python module `meshrepair` on NumPy arrays: geometry in, geometry out."""

import threading
import time

import numpy as np
import pytest

import meshrepair
from conftest import signed_volume, subdivided_cube, tet_volumes


def assert_watertight(vertices, faces):
    report = meshrepair.check(vertices, faces)
    assert report["watertight"], report["problems"]
    assert report["closed"] and report["manifold"]
    assert report["self_intersecting_pairs"] == 0
    return report


# --- repair -----------------------------------------------------------------


def test_repair_cube_round_trip(cube):
    vertices, faces = meshrepair.repair(*cube)
    assert vertices.dtype == np.float64 and vertices.shape[1] == 3
    assert faces.dtype == np.int64 and faces.shape[1] == 3
    report = assert_watertight(vertices, faces)
    assert report["components"] == 1
    assert signed_volume(vertices, faces) == pytest.approx(1.0, abs=1e-2)
    # Within epsilon (1e-3 of the diagonal) of the cube.
    assert np.all(vertices >= -2e-3) and np.all(vertices <= 1 + 2e-3)


def test_repair_soup_cube_is_closed(soup_cube):
    vertices, faces = soup_cube
    before = meshrepair.check(vertices, faces)
    assert before["duplicate_faces"] == 12 and not before["manifold"] and not before["watertight"]
    vertices, faces = meshrepair.repair(vertices, faces)
    assert_watertight(vertices, faces)
    assert len(np.unique(vertices, axis=0)) == len(vertices)  # welded
    assert signed_volume(vertices, faces) == pytest.approx(1.0, abs=1e-2)


def test_repair_inward_cube_comes_out_outward(cube):
    vertices, faces = cube
    vertices, faces = meshrepair.repair(vertices, faces[:, ::-1], remesh=True)
    assert_watertight(vertices, faces)
    assert signed_volume(vertices, faces) == pytest.approx(1.0, abs=1e-2)


def test_repair_of_holes_only_keeps_every_face(open_cube):
    vertices, faces = meshrepair.repair(*open_cube)
    assert_watertight(vertices, faces)
    # The input's ten faces come first, unchanged; the patch closes the top.
    np.testing.assert_array_equal(vertices[faces[:10]], open_cube[0][open_cube[1]])
    assert signed_volume(vertices, faces) == pytest.approx(1.0, abs=1e-9)


def test_repair_cuts_a_fold_out_and_keeps_every_face_away_from_it():
    n = 8
    vertices, faces = subdivided_cube(n)
    # The middle vertex of the top side moved along it past its neighbour:
    # its fan folds over the faces beyond.
    middle = np.array([0.5, 0.5, 1.0])
    v = np.flatnonzero(np.all(vertices == middle, axis=1))[0]
    vertices[v, 0] += 1.6 / n
    assert meshrepair.check(vertices, faces)["self_intersecting_pairs"] > 0
    out_vertices, out_faces = meshrepair.repair(vertices, faces)
    assert_watertight(out_vertices, out_faces)

    def corner_sets(vs, fs):
        return {tuple(sorted(map(tuple, vs[f]))) for f in fs}

    far = np.linalg.norm(vertices[faces].mean(axis=1) - middle, axis=1) > 4.0 / n
    assert far.sum() > 0.8 * len(faces)
    assert corner_sets(vertices, faces[far]) <= corner_sets(out_vertices, out_faces)


def test_repair_takes_the_outer_hull_past_its_tet_budget(cube):
    vertices, faces = cube
    two = np.concatenate([vertices, vertices + 0.5]), np.concatenate([faces, faces + len(vertices)])
    exact = meshrepair.repair(*two, remesh=True, max_tets=0)
    assert_watertight(*exact)
    assert signed_volume(*exact) == pytest.approx(2.0 - 0.125, abs=1e-2)
    hull = meshrepair.repair(*two, remesh=True, max_tets=1)
    assert_watertight(*hull)
    # The union grown by about a voxel (at most 1.5/96 here) on every side.
    assert 2.0 - 0.125 < signed_volume(*hull) < 2.0 - 0.125 + 10 * 2 * 1.5 / 96
    assert not np.array_equal(exact[1], hull[1])


def test_repair_accepts_float32_and_strided_arrays(cube):
    vertices, faces = cube
    strided = np.asfortranarray(vertices.astype(np.float32))
    assert not strided.flags["C_CONTIGUOUS"]
    v, f = meshrepair.repair(strided, faces.astype(np.int32)[::1, ::1])
    assert_watertight(v, f)
    assert signed_volume(v, f) == pytest.approx(1.0, abs=1e-2)


def test_repair_float32_grid_puts_positions_on_float32(cube):
    vertices, faces = meshrepair.repair(cube[0] * 0.1 + 0.3, cube[1], remesh=True, grid="float32")
    np.testing.assert_array_equal(vertices.astype(np.float32).astype(np.float64), vertices)
    assert_watertight(vertices, faces)


# --- tetrahedralize and check_tets ---------------------------------------


def test_tetrahedralize_cube_round_trip(cube):
    vertices, tets = meshrepair.tetrahedralize(*cube)
    assert tets.shape[1] == 4 and tets.dtype == np.int64
    assert tets.min() >= 0 and tets.max() < len(vertices)
    volumes = tet_volumes(vertices, tets)
    assert np.all(volumes > 0)
    assert volumes.sum() == pytest.approx(1.0, abs=1e-2)
    report = meshrepair.check_tets(vertices, tets)
    assert report["valid"] and report["inverted_tets"] == 0
    assert report["tets"] == len(tets)
    assert report["boundary"]["watertight"]
    assert report["volume"] == pytest.approx(volumes.sum())


def test_tetrahedralize_returns_labels(cube):
    vertices, tets, labels = meshrepair.tetrahedralize(*cube, return_labels=True)
    assert labels.shape == (len(tets),) and np.all(labels == 1)


def test_tetrahedralize_labels_tets_by_face_region(cube):
    vertices, faces = cube
    right = np.asarray(vertices, dtype=float) + [1.0, 0.0, 0.0]
    both = np.vstack([vertices, right])
    all_faces = np.vstack([faces, np.asarray(faces) + len(vertices)])
    regions = np.repeat([0, 1], len(faces))
    v, t, labels = meshrepair.tetrahedralize(both, all_faces, face_regions=regions, max_passes=0,
                                             return_labels=True)
    # Slivers on the interface (no improvement) have centroids within
    # rounding of x = 1: judged by their volume below, not their side.
    centroid_x = v[t].mean(axis=1)[:, 0]
    clear = np.abs(centroid_x - 1.0) > 1e-9
    assert np.array_equal(labels[clear], np.where(centroid_x[clear] < 1.0, 1, 2))
    volumes = tet_volumes(v, t)
    assert volumes[labels == 1].sum() == pytest.approx(1.0, abs=1e-9)
    assert volumes[labels == 2].sum() == pytest.approx(1.0, abs=1e-9)
    _, _, plain = meshrepair.tetrahedralize(both, all_faces, face_regions=regions, labels="none",
                                            max_passes=0, return_labels=True)
    assert np.all(plain == 1)
    with pytest.raises(ValueError, match="face_regions"):
        meshrepair.tetrahedralize(both, all_faces, face_regions=regions[:3])
    with pytest.raises(ValueError, match="labels"):
        meshrepair.tetrahedralize(both, all_faces, labels="materials")


def test_tetrahedralize_follows_a_sizing_field(cube):
    # A box of 6 tets over [-1, 2]^3 whose values give 0.11 to 0.13 over
    # the unit cube, against a global target of 0.3.
    corners = np.array([[x, y, z] for z in (-1, 2) for y in (-1, 2) for x in (-1, 2)], dtype=float)
    kuhn = np.array([[0, 1, 3, 7], [0, 1, 5, 7], [0, 2, 3, 7], [0, 2, 6, 7], [0, 4, 5, 7], [0, 4, 6, 7]])
    values = np.where(corners[:, 0] < 0, 0.08, 0.16)
    plain = meshrepair.tetrahedralize(*cube, edge_length_abs=0.3, lattice=0)[1]
    graded = meshrepair.tetrahedralize(*cube, edge_length_abs=0.3, lattice=0,
                                       sizing=(corners, kuhn, values))[1]
    assert len(graded) > 4 * len(plain)
    with pytest.raises(ValueError, match="sizing"):
        meshrepair.tetrahedralize(*cube, sizing=(corners, kuhn))
    with pytest.raises(ValueError, match="sizing"):
        meshrepair.tetrahedralize(*cube, sizing=(corners, kuhn, values[:3]))
    with pytest.raises(meshrepair.InputError, match="positive"):
        meshrepair.tetrahedralize(*cube, sizing=(corners, kuhn, -values))


def test_check_tets_finds_inverted_tet():
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    good = meshrepair.check_tets(vertices, [[0, 1, 2, 3]])
    bad = meshrepair.check_tets(vertices, [[0, 2, 1, 3]])
    assert good["valid"] and good["volume"] == pytest.approx(1 / 6)
    assert not bad["valid"] and bad["inverted_tets"] == 1


# --- simplify, fill_holes, check -------------------------------------------


def test_simplify_subdivided_cube():
    vertices, faces = subdivided_cube(8)
    assert len(faces) == 6 * 2 * 64
    v, f = meshrepair.simplify(vertices, faces)
    assert len(f) < len(faces) / 4
    # Positions are a subset of the input's; the cube stays a closed cube.
    assert np.isin(v.view([("", v.dtype)] * 3), vertices.view([("", vertices.dtype)] * 3)).all()
    report = meshrepair.check(v, f)
    assert report["closed"] and report["manifold"]
    assert signed_volume(v, f) == pytest.approx(1.0, abs=1e-6)


def test_fill_holes_reports_each_hole(open_cube):
    vertices, faces, report = meshrepair.fill_holes(*open_cube)
    assert report["holes_found"] == 1 and report["holes_filled"] == 1
    assert report["input_faces"] == 10
    (hole,) = report["holes"]
    assert hole["outcome"] == "filled" and hole["border_edges"] == 4
    assert len(faces) == 10 + hole["patch_faces"]
    assert_watertight(vertices, faces)


def test_fill_holes_leaves_too_long_holes_open(open_cube):
    vertices, faces, report = meshrepair.fill_holes(*open_cube, max_boundary=3)
    assert report["holes_filled"] == 0 and report["holes"][0]["outcome"] == "too_long"
    assert len(faces) == 10
    assert meshrepair.check(vertices, faces)["boundary_edges"] == 4


def test_check_counts_defects(cube, open_cube):
    assert meshrepair.check(*cube)["watertight"]
    report = meshrepair.check(*open_cube)
    assert not report["closed"] and report["boundary_edges"] == 4
    assert "boundary" in report["problems"]
    report = meshrepair.check(*cube, self_intersections=False)
    assert report["self_intersecting_pairs"] is None and not report["watertight"]


# --- files --------------------------------------------------------------------


@pytest.mark.parametrize("extension", ["obj", "off", "ply", "stl", "glb"])
def test_write_read_round_trip(cube, tmp_path, extension):
    path = tmp_path / f"cube.{extension}"
    meshrepair.write(path, *cube)
    vertices, faces = meshrepair.read(str(path))
    assert len(faces) == 12
    assert signed_volume(vertices, faces) == pytest.approx(1.0)
    assert meshrepair.check(vertices, faces)["watertight"]


def test_tets_round_trip(cube, tmp_path):
    vertices, tets = meshrepair.tetrahedralize(*cube)
    path = tmp_path / "cube.msh"
    meshrepair.write_tets(path, vertices, tets)
    v, t = meshrepair.read_tets(path)
    assert len(t) == len(tets)
    assert tet_volumes(v, t).sum() == pytest.approx(1.0, abs=1e-2)


def test_read_missing_file_raises_input_error(tmp_path):
    missing = tmp_path / "missing.stl"
    with pytest.raises(meshrepair.InputError, match="missing.stl"):
        meshrepair.read(missing)
    assert issubclass(meshrepair.InputError, meshrepair.Error)
    assert issubclass(meshrepair.Error, RuntimeError)


# --- bad arrays and options ---------------------------------------------------


@pytest.mark.parametrize(
    "vertices, faces, message",
    [
        (np.zeros((8, 2)), [[0, 1, 2]], r"vertices must have shape \(N, 3\), got \(8, 2\)"),
        (np.zeros(24), [[0, 1, 2]], r"vertices must have shape \(N, 3\), got \(24,\)"),
        ([["a", "b", "c"]], [[0, 0, 0]], "vertices must be an array of real numbers"),
        (None, [[0, 1, 2]], "vertices must be an array of real numbers"),
        (np.eye(3), np.array([[0.0, 1.0, 2.0]]), "faces must be an array of integers, got dtype float64"),
        (np.eye(3), [[0, 1]], r"faces must have shape \(N, 3\)"),
        (np.eye(3), [[0, 1, 3]], r"faces\[0, 2\] = 3 is not a vertex index \(there are 3 vertices\)"),
        (np.eye(3), [[0, -1, 2]], r"faces\[0, 1\] = -1 is not a vertex index"),
        (np.array([[0, 0, 0], [1, 0, np.nan], [0, 1, 0]]), [[0, 1, 2]], r"vertices\[1\] is not finite"),
        (np.array([[0, 0, 0], [1, 0, 0], [0, np.inf, 0]]), [[0, 1, 2]], r"vertices\[2\] is not finite"),
    ],
)
@pytest.mark.parametrize("function", [meshrepair.repair, meshrepair.tetrahedralize, meshrepair.simplify,
                                      meshrepair.fill_holes, meshrepair.check])
def test_bad_arrays_raise_value_error(function, vertices, faces, message):
    with pytest.raises(ValueError, match=message):
        function(vertices, faces)


def test_bad_tets_raise_value_error():
    with pytest.raises(ValueError, match=r"tets must have shape \(N, 4\)"):
        meshrepair.check_tets(np.eye(3), [[0, 1, 2]])
    with pytest.raises(ValueError, match=r"tets\[0, 3\] = 7"):
        meshrepair.check_tets(np.eye(4)[:, :3], [[0, 1, 2, 7]])


def test_bad_options_raise(cube):
    with pytest.raises(ValueError, match="threads must be >= 0"):
        meshrepair.repair(*cube, threads=-1)
    with pytest.raises(ValueError, match="grid must be"):
        meshrepair.repair(*cube, grid="float16")
    with pytest.raises(ValueError, match="max_tets"):
        meshrepair.repair(*cube, max_tets=-1)
    with pytest.raises(ValueError, match="epsilon"):
        meshrepair.tetrahedralize(*cube, epsilon=-1.0)
    with pytest.raises(ValueError, match="density"):
        meshrepair.fill_holes(*cube, density="dense")
    with pytest.raises(TypeError):
        meshrepair.repair(*cube, epsilom=1e-3)


@pytest.mark.parametrize("function", [meshrepair.repair, meshrepair.tetrahedralize])
def test_run_failure_raises_the_tools_message(function):
    # All vertices at one point: a valid array, but nothing to mesh.
    with pytest.raises(meshrepair.Error, match="bounding box has no extent.*nothing to tetrahedralize"):
        function(np.zeros((3, 3)), [[0, 1, 2]])


# --- the GIL ------------------------------------------------------------------


def test_concurrent_repairs_match_a_sequential_one(cube):
    vertices, faces = subdivided_cube(6)
    expected = meshrepair.repair(vertices, faces, remesh=True, threads=1)
    results = [None, None]

    def work(slot):
        results[slot] = meshrepair.repair(vertices, faces, remesh=True, threads=1)

    threads = [threading.Thread(target=work, args=(slot,)) for slot in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for v, f in results:
        np.testing.assert_array_equal(v, expected[0])
        np.testing.assert_array_equal(f, expected[1])


def test_repair_releases_the_gil():
    # While a repair runs in another thread, this thread keeps running Python:
    # the longest pause it sees is far shorter than the repair.
    vertices, faces = subdivided_cube(12)
    span = {}

    def work():
        start = time.perf_counter()
        meshrepair.repair(vertices, faces, remesh=True, threads=1)
        span["seconds"] = time.perf_counter() - start

    thread = threading.Thread(target=work)
    longest_pause, last = 0.0, time.perf_counter()
    thread.start()
    while thread.is_alive():
        now = time.perf_counter()
        longest_pause, last = max(longest_pause, now - last), now
    thread.join()
    assert span["seconds"] > 0.1, "the repair is too quick to tell"
    assert longest_pause < span["seconds"] / 2
