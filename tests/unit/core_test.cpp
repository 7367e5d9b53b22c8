#include "test_support.h"

#include <mr/core/boundary.h>
#include <mr/core/errors.h>
#include <mr/core/grid_snap.h>
#include <mr/core/openmesh_convert.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

using namespace mr;

TEST_CASE("soup consistency check finds bad indices and non-finite coordinates", "[core]") {
  TriangleSoup soup = test::cube_soup();
  CHECK(find_soup_inconsistency(soup).empty());
  soup.triangles.push_back({0, 1, 8});
  CHECK_THAT(find_soup_inconsistency(soup), Catch::Contains("refers to vertex 8"));
  soup = test::cube_soup();
  soup.positions[3].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(find_soup_inconsistency(soup), Catch::Contains("non-finite"));
  soup = test::cube_soup();
  soup.normals.resize(3);
  CHECK_THAT(find_soup_inconsistency(soup), Catch::Contains("normals"));
}

TEST_CASE("soup append offsets indices and keeps shared attributes only", "[core]") {
  TriangleSoup a = test::cube_soup();
  a.face_regions.assign(a.triangles.size(), 1);
  TriangleSoup b = test::cube_soup(2, 3);
  a.append(b);
  CHECK(a.num_vertices() == 16);
  CHECK(a.num_triangles() == 24);
  CHECK(a.triangles[12][0] == b.triangles[0][0] + 8);
  REQUIRE(a.face_regions.size() == 24);
  CHECK(a.face_regions[0] == 1);
  CHECK(a.face_regions[23] == 0);
  CHECK(find_soup_inconsistency(a).empty());
}

TEST_CASE("cube soup encloses unit volume with outward faces", "[core]") {
  CHECK(test::enclosed_volume(test::cube_soup()) == Approx(1.0));
  CHECK(bounding_box_diagonal(test::cube_soup()) == Approx(std::sqrt(3.0)));
}

TEST_CASE("boundary of a tet mesh is closed and outward", "[core][boundary]") {
  const TetMesh mesh = test::cube_tets();
  CHECK(test::tet_volume(mesh) == Approx(1.0));
  const TriangleSoup boundary = extract_boundary(mesh);
  CHECK(boundary.num_triangles() == 12);
  CHECK(boundary.num_vertices() == 8);
  CHECK(test::enclosed_volume(boundary) == Approx(1.0));

  const TriangleSoup half = extract_boundary(mesh, [](std::size_t t) { return t < 3; });
  CHECK(test::enclosed_volume(half) == Approx(0.5));

  const TriangleSoup labelled = extract_boundary(mesh, {}, true);
  REQUIRE(labelled.face_regions.size() == 12);
}

TEST_CASE("interfaces between labels are extracted once each", "[core][boundary]") {
  const TetMesh mesh = test::cube_tets();  // six labels: every inner face is an interface
  const TriangleSoup interfaces = extract_interfaces(mesh);
  // 12 outer faces + 6 inner faces (each of the 6 tets shares 2 faces with neighbours).
  CHECK(interfaces.num_triangles() == 18);
}

TEST_CASE("halfedge conversion reports the faces it cannot hold", "[core][openmesh]") {
  const TriangleSoup soup = test::non_manifold_soup();
  const ToTriMeshResult result = to_trimesh(soup);
  CHECK(result.mesh.n_vertices() == soup.num_vertices());
  CHECK(result.mesh.n_faces() + result.rejected_triangles.size() == soup.num_triangles());
  CHECK_FALSE(result.rejected_triangles.empty());

  const ToTriMeshResult cube = to_trimesh(test::cube_soup());
  CHECK(cube.rejected_triangles.empty());
  const TriangleSoup back = to_soup(cube.mesh);
  CHECK(back.triangles == test::cube_soup().triangles);
  CHECK(back.positions == test::cube_soup().positions);
}

TEST_CASE("halfedge conversion writes nothing to OpenMesh's error stream", "[core][openmesh]") {
  TriangleSoup soup;
  for (int i = 0; i < 10; ++i) soup.positions.emplace_back(std::cos(i), std::sin(i), 0.1 * i);
  soup.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4},  // an open fan around vertex 0
                    {0, 5, 6},                        // a second fan at vertex 0
                    {0, 4, 1},                        // would close the first fan: re-linking fails
                    {0, 1, 2},                        // a duplicate: complex edge
                    {1, 2, 7},                        // reuses halfedge 1->2: complex edge
                    {7, 8, 9}, {8, 7, 9}, {7, 9, 8},  // two faces close a pillow, the third is a complex edge
                    {9, 3, 8},                        // touches the closed pillow: complex vertex
                    {5, 5, 6}};                       // a repeated index
  const test::CapturedStderr captured;
  const ToTriMeshResult result = to_trimesh(soup);
  CHECK(captured.text().empty());
  CHECK(result.rejected_triangles == std::vector<std::size_t>{4, 5, 6, 9, 10, 11});
  CHECK(result.mesh.n_faces() + result.rejected_triangles.size() == soup.num_triangles());
}

TEST_CASE("can_add_face tells exactly which faces OpenMesh's add_face refuses", "[core][openmesh]") {
  std::mt19937 random(7);
  std::size_t refused = 0;
  std::size_t disagreements = 0;
  std::size_t log_lines = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    TriMesh mesh;
    const int vertices = 4 + int(random() % 8);
    std::vector<TriMesh::VertexHandle> v;
    for (int i = 0; i < vertices; ++i) v.push_back(mesh.add_vertex(TriMesh::Point(i, 0, 0)));
    for (int k = 0; k < 30; ++k) {
      const auto a = v[random() % v.size()], b = v[random() % v.size()], c = v[random() % v.size()];
      if (a == b || b == c || a == c) {
        CHECK_FALSE(can_add_face(mesh, a, b, c));
        continue;
      }
      const bool predicted = can_add_face(mesh, a, b, c);
      const test::CapturedStderr captured;
      const bool added = mesh.add_face(a, b, c).is_valid();
      disagreements += predicted != added;
      refused += !added;
      const std::string text = captured.text();
      log_lines += std::size_t(std::count(text.begin(), text.end(), '\n'));
    }
  }
  CHECK(disagreements == 0);
  CHECK(refused > 1000);        // all three kinds of refusal occur
  CHECK(log_lines == refused);  // add_face logs each refusal: what to_trimesh avoids
}

TEST_CASE("grid snapping rounds to the nearest multiple of a power of two", "[core][snap]") {
  CHECK(power_of_two_at_most(1.0) == 1.0);
  CHECK(power_of_two_at_most(0.75) == 0.5);
  CHECK(power_of_two_at_most(1e-3) == std::ldexp(1.0, -10));
  TriangleSoup soup;
  soup.positions = {{1.0 + 1e-12, -0.3, 7.0}, {0.5, 0.25, -0.125}, {-1e-9, 3.0 * 0.0625 + 0.03, 0.09375}};
  soup.triangles = {{0, 1, 2}};
  const TriangleSoup before = soup;
  const double spacing = 0.0625;
  CHECK(snap_to_grid(soup, spacing) == 2);  // the second vertex is on the grid already
  CHECK(soup.positions[0] == Vec3d(1.0, -0.3125, 7.0));
  CHECK(soup.positions[1] == before.positions[1]);
  CHECK(soup.positions[2] == Vec3d(0.0, 0.1875, 0.125));  // 0.09375 is 1.5 steps: a tie, to even
  CHECK(soup.triangles == before.triangles);
  for (std::size_t i = 0; i < soup.positions.size(); ++i) {
    CHECK((soup.positions[i] - before.positions[i]).norm() <= spacing * std::sqrt(3.0) / 2);
    for (int axis = 0; axis < 3; ++axis) {
      const double steps = soup.positions[i][axis] / spacing;
      CHECK(steps == std::round(steps));
    }
  }
}
