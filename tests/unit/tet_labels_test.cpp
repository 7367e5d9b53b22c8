// tetrahedralize labels the kept tets by the input part they lie in: face
// regions (glTF materials, OBJ groups), connected components or winding
// levels. Every tet's label is checked against where its centroid lies.

#include "test_support.h"

#include <mr/core/errors.h>
#include <mr/tetmesh/tetrahedralize.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <map>

using namespace mr;

namespace {

TriangleSoup box(const Vec3d& lo, const Vec3d& hi, std::int32_t region) {
  TriangleSoup soup = test::cube_soup();
  for (Vec3d& p : soup.positions) p = lo + p.cwiseProduct(hi - lo);
  soup.face_regions.assign(soup.triangles.size(), region);
  return soup;
}

TriangleSoup merged(TriangleSoup a, const TriangleSoup& b) {
  a.append(b);
  return a;
}

Vec3d centroid(const TetMesh& mesh, const Tet& t) {
  return (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]] + mesh.positions[t[3]]) / 4;
}

double volume(const TetMesh& mesh, const Tet& t) {
  const auto& p = mesh.positions;
  return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(p[t[3]] - p[t[0]]) / 6;
}

std::map<std::int32_t, double> volume_per_label(const TetMesh& mesh) {
  std::map<std::int32_t, double> volumes;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    volumes[mesh.tet_labels[t]] += volume(mesh, mesh.tets[t]);
  return volumes;
}

tetmesh::PipelineResult run(const TriangleSoup& input, tetmesh::TetLabels labels) {
  tetmesh::PipelineOptions options;
  options.improve = false;
  options.labels = labels;
  options.tetrahedralize.threads = 2;
  return tetmesh::tetrahedralize(input, options);
}

// Two unit boxes side by side along x, touching on the plane x = 1.
TriangleSoup touching_boxes() {
  TriangleSoup soup = merged(box({0, 0, 0}, {1, 1, 1}, 0), box({1, 0, 0}, {2, 1, 1}, 1));
  soup.region_names = {"steel", "rubber"};
  return soup;
}

}  // namespace

TEST_CASE("tet labels: two touching boxes with a region each get a label each, named",
          "[tetrahedralize][labels]") {
  const TetMesh mesh = run(touching_boxes(), tetmesh::TetLabels::automatic).mesh;
  REQUIRE(mesh.tet_labels.size() == mesh.tets.size());
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const double x = centroid(mesh, mesh.tets[t]).x();
    CAPTURE(t, x);
    // Slivers on the interface (no improvement) count by their volume below.
    if (std::abs(x - 1) > 1e-9) CHECK(mesh.tet_labels[t] == (x < 1 ? 1 : 2));
  }
  const std::map<std::int32_t, double> volumes = volume_per_label(mesh);
  REQUIRE(volumes.size() == 2);
  CHECK(volumes.at(1) == Approx(1.0).epsilon(1e-9));
  CHECK(volumes.at(2) == Approx(1.0).epsilon(1e-9));
  CHECK(mesh.tet_label_names == std::map<std::int32_t, std::string>{{1, "steel"}, {2, "rubber"}});
}

TEST_CASE("tet labels: none gives label 1 everywhere", "[tetrahedralize][labels]") {
  const TetMesh mesh = run(touching_boxes(), tetmesh::TetLabels::none).mesh;
  CHECK(volume_per_label(mesh).size() == 1);
  CHECK(volume_per_label(mesh).at(1) == Approx(2.0).epsilon(1e-9));
  CHECK(mesh.tet_label_names.empty());
}

TEST_CASE("tet labels: components label separate bodies of an input without regions",
          "[tetrahedralize][labels]") {
  TriangleSoup bodies = merged(box({0, 0, 0}, {1, 1, 1}, 0), box({1.5, 0, 0}, {2.5, 1, 1}, 0));
  bodies.face_regions.clear();
  CHECK(volume_per_label(run(bodies, tetmesh::TetLabels::automatic).mesh).size() == 1);
  const TetMesh mesh = run(bodies, tetmesh::TetLabels::components).mesh;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    CHECK(mesh.tet_labels[t] == (centroid(mesh, mesh.tets[t]).x() < 1.25 ? 1 : 2));
  CHECK(volume_per_label(mesh).size() == 2);
}

TEST_CASE("tet labels: winding labels the nesting depth", "[tetrahedralize][labels]") {
  // An outward box inside an outward box: winding number 2 in the inner one.
  const TriangleSoup nested = merged(box({0, 0, 0}, {3, 3, 3}, 0), box({1, 1, 1}, {2, 2, 2}, 0));
  const TetMesh mesh = run(nested, tetmesh::TetLabels::winding).mesh;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const Vec3d c = centroid(mesh, mesh.tets[t]);
    const bool inner = c.minCoeff() > 1 && c.maxCoeff() < 2;
    CHECK(mesh.tet_labels[t] == (inner ? 2 : 1));
  }
  const std::map<std::int32_t, double> volumes = volume_per_label(mesh);
  REQUIRE(volumes.size() == 2);
  CHECK(volumes.at(2) == Approx(1.0).epsilon(1e-9));
  CHECK(volumes.at(1) == Approx(26.0).epsilon(1e-9));
}

TEST_CASE("tet labels: an inclusion inside its host part goes to the inclusion", "[tetrahedralize][labels]") {
  // A closed "ball" (region 1) modelled inside a closed "block" (region 0):
  // winding 1 for both in the ball; the innermost part wins.
  TriangleSoup input = merged(box({0, 0, 0}, {3, 3, 3}, 0), box({1, 1, 1}, {2, 2, 2}, 1));
  const TetMesh mesh = run(input, tetmesh::TetLabels::automatic).mesh;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const Vec3d c = centroid(mesh, mesh.tets[t]);
    CHECK(mesh.tet_labels[t] == (c.minCoeff() > 1 && c.maxCoeff() < 2 ? 2 : 1));
  }
  const std::map<std::int32_t, double> volumes = volume_per_label(mesh);
  REQUIRE(volumes.size() == 2);
  CHECK(volumes.at(1) == Approx(26.0).epsilon(1e-9));
  CHECK(volumes.at(2) == Approx(1.0).epsilon(1e-9));
}
