// Stage 3: the background Delaunay mesh with voxel stuffing.

#include "test_support.h"

#include <mr/check/tet_check.h>
#include <mr/core/errors.h>
#include <mr/tetmesh/background_mesh.h>
#include <mr/tetmesh/convert.h>
#include <mr/tetmesh/incidence.h>
#include <mr/tetmesh/mesh_check.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <set>

using namespace mr;
using namespace mr::tetmesh;

namespace {

// Distance from p to the surface of the unit cube [0, 1]^3, computed directly.
double distance_to_unit_cube(const Vec3d& p) {
  const Vec3d clamped = p.cwiseMax(Vec3d::Zero()).cwiseMin(Vec3d::Ones());
  if (clamped != p) return (p - clamped).norm();
  return std::min(p.minCoeff(), (Vec3d::Ones() - p).minCoeff());
}

BackgroundMesh background_of(const TriangleSoup& soup, const TetrahedralizeOptions& options = {},
                             bool parallel = true) {
  const DerivedParameters derived = derive_parameters(options, soup);
  BackgroundParameters parameters = background_parameters(derived, options.threads);
  parameters.parallel = parallel;
  return build_background_mesh(soup, spatial::AabbTree(soup), parameters);
}

// A closed, bumpy sphere-like soup with pseudo-random radii (fixed seed).
TriangleSoup bumpy_sphere(int rings, int sectors, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> radius(0.8, 1.2);
  TriangleSoup soup;
  soup.positions.emplace_back(0, 0, 1);
  for (int i = 1; i < rings; ++i) {
    const double theta = M_PI * i / rings;
    for (int j = 0; j < sectors; ++j) {
      const double phi = 2 * M_PI * j / sectors;
      soup.positions.push_back(radius(rng) * Vec3d(std::sin(theta) * std::cos(phi),
                                                   std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  }
  soup.positions.emplace_back(0, 0, -1);
  const auto ring = [&](int i, int j) { return Index(1 + (i - 1) * sectors + (j % sectors)); };
  const Index south = Index(soup.positions.size() - 1);
  for (int j = 0; j < sectors; ++j) {
    soup.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
    soup.triangles.push_back({south, ring(rings - 1, j + 1), ring(rings - 1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      soup.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      soup.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  }
  return soup;
}

}  // namespace

TEST_CASE("tetmesh: background mesh of a cube is valid and covers the box", "[tetmesh]") {
  const TriangleSoup cube = test::cube_soup();
  const TetrahedralizeOptions options;
  const DerivedParameters derived = derive_parameters(options, cube);
  const BackgroundMesh background = background_of(cube, options);
  const Mesh& mesh = background.mesh;

  CHECK(find_mesh_inconsistency(mesh).empty());
  const TetMesh out = to_tet_mesh(mesh);
  const check::TetReport report = check::check_tets(out);
  CHECK(report.valid());
  CHECK(report.inverted_tets == 0);
  CHECK(report.degenerate_tets == 0);

  const double box_volume = (derived.box_max - derived.box_min).prod();
  CHECK(std::abs(test::tet_volume(out) - box_volume) <= 1e-9 * box_volume);
  CHECK(background.distinct_input_vertices == 8);
  CHECK(background.lattice_points > 0);
  CHECK(mesh.num_vertices() == 8 + 8 + background.lattice_points);

  // Every input vertex is a mesh vertex at exactly its position, used by tets.
  const VertexTets incidence(mesh);
  for (std::size_t i = 0; i < cube.positions.size(); ++i) {
    const Index v = background.input_vertex[i];
    CHECK(mesh.position(v).approx == cube.positions[i]);
    CHECK(!mesh.position(v).is_exact());
    CHECK(!incidence.of(v).empty());
  }
  // Every vertex is used, and the box corners carry the box flag.
  for (Index v = 0; v < mesh.vertex_slots(); ++v) CHECK(!incidence.of(v).empty());
  for (Index v = 8; v < 16; ++v) CHECK(mesh.has_flag(v, kOnBox));
  // The hull is the box: 2 triangles per lattice square on each box face.
  std::size_t hull_faces = 0;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    for (int f = 0; f < 4; ++f) {
      if (mesh.neighbour(t, f) != kNoTet) continue;
      ++hull_faces;
      for (const Index v : mesh.face_vertices(t, f)) CHECK(mesh.has_flag(v, kOnBox));
    }
  }
  CHECK(hull_faces == report.boundary.faces);
  CHECK(report.boundary.watertight());
  CHECK(std::abs(report.boundary.volume - box_volume) <= 1e-9 * box_volume);
}

TEST_CASE("tetmesh: voxel stuffing keeps exactly the lattice points farther than delta", "[tetmesh]") {
  const TriangleSoup cube = test::cube_soup();
  const DerivedParameters derived = derive_parameters({}, cube);
  const double delta = derived.lattice_clearance;
  REQUIRE(delta == Approx(std::sqrt(3.0) / 40));
  const std::vector<Vec3d> all = lattice_points(derived.box_min, derived.box_max, derived.lattice_spacing);
  const std::vector<Vec3d> kept = voxel_stuffing_points(
      derived.box_min, derived.box_max, derived.lattice_spacing, delta, spatial::AabbTree(cube));
  const std::set<std::array<double, 3>> kept_set = [&] {
    std::set<std::array<double, 3>> s;
    for (const Vec3d& p : kept) s.insert({p.x(), p.y(), p.z()});
    return s;
  }();
  std::size_t removed_near = 0, corners = 0;
  for (const Vec3d& p : all) {
    const bool corner =
        ((p.array() == derived.box_min.array()) || (p.array() == derived.box_max.array())).all();
    corners += corner;
    const bool is_kept = kept_set.count({p.x(), p.y(), p.z()}) > 0;
    if (corner) {
      CHECK(!is_kept);
    } else if (is_kept) {
      CHECK(distance_to_unit_cube(p) > delta);
    } else {
      CHECK(distance_to_unit_cube(p) <= delta);
      ++removed_near;
    }
  }
  CHECK(corners == 8);
  CHECK(removed_near > 0);
  CHECK(kept.size() + removed_near + 8 == all.size());
  // The spacing is the paper's b/20 up to rounding to whole intervals.
  CHECK(std::abs((all[1] - all[0]).norm() - derived.lattice_spacing) < 0.1 * derived.lattice_spacing);
}

TEST_CASE("tetmesh: background mesh is deterministic, parallel or not", "[tetmesh]") {
  const TriangleSoup soup = bumpy_sphere(24, 40, 7);
  const BackgroundMesh first = background_of(soup);
  const BackgroundMesh second = background_of(soup);
  const BackgroundMesh sequential = background_of(soup, {}, false);
  TetrahedralizeOptions one_thread;
  one_thread.threads = 1;
  const BackgroundMesh single = background_of(soup, one_thread);

  const TetMesh a = to_tet_mesh(first.mesh);
  CHECK(find_mesh_inconsistency(first.mesh).empty());
  CHECK(check::check_tets(a).valid());
  for (const BackgroundMesh* other : {&second, &sequential, &single}) {
    const TetMesh b = to_tet_mesh(other->mesh);
    CHECK(a.positions == b.positions);
    CHECK(a.tets == b.tets);
    for (Index t = 0; t < first.mesh.tet_slots(); ++t) {
      for (int f = 0; f < 4; ++f) CHECK(first.mesh.neighbour(t, f) == other->mesh.neighbour(t, f));
    }
  }
}

TEST_CASE("tetmesh: background mesh merges equal input vertices", "[tetmesh]") {
  TriangleSoup soup = test::cube_soup();
  soup.append(test::cube_soup());
  for (std::size_t i = 8; i < 16; ++i) {
    if (soup.positions[i].x() == 0.0) soup.positions[i].x() = -0.0;  // equals 0.0: still merged
  }
  soup.positions.emplace_back(0.5, 0.5, 0.5);  // unreferenced, still a vertex
  TetrahedralizeOptions options;
  options.lattice_spacing_rel = 0.0;
  const BackgroundMesh background = background_of(soup, options);
  CHECK(background.distinct_input_vertices == 9);
  CHECK(background.lattice_points == 0);
  CHECK(background.mesh.num_vertices() == 17);
  for (std::size_t i = 0; i < 8; ++i) CHECK(background.input_vertex[i] == background.input_vertex[i + 8]);
  CHECK(find_mesh_inconsistency(background.mesh).empty());
  CHECK(check::check_tets(to_tet_mesh(background.mesh)).valid());
}

TEST_CASE("tetmesh: background mesh refuses a box that does not contain the input", "[tetmesh]") {
  const TriangleSoup cube = test::cube_soup();
  BackgroundParameters parameters;
  parameters.box_min = Vec3d::Zero();  // touches the input: not strictly around it
  parameters.box_max = Vec3d::Constant(2.0);
  CHECK_THROWS_AS(build_background_mesh(cube, spatial::AabbTree(cube), parameters), UsageError);
  CHECK_THROWS_AS(lattice_points(Vec3d::Zero(), Vec3d::Ones(), 1e-4), UsageError);
}
