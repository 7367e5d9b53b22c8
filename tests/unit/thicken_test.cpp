// Sheets that enclose no volume: thicken_sheets makes closed prisms of them,
// and the pipeline falls back to that instead of returning an empty mesh.

#include "test_support.h"

#include <mr/check/distance.h>
#include <mr/check/tet_check.h>
#include <mr/core/thicken.h>
#include <mr/tetmesh/tetrahedralize.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <utility>

using namespace mr;

namespace {

// Three unit squares through the origin, one per coordinate plane, each
// face present with both orientations (as libigl's degenerated.obj): every
// edge is non-manifold and the winding number is zero everywhere.
TriangleSoup crossing_doubled_sheets() {
  TriangleSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  const std::vector<Triangle> sheet = {{0, 1, 2}, {0, 1, 5}, {0, 1, 3}, {0, 1, 6}, {0, 4, 2}, {0, 4, 5},
                                       {0, 4, 3}, {0, 4, 6}, {0, 2, 3}, {0, 5, 3}, {0, 2, 6}, {0, 5, 6}};
  for (const Triangle& t : sheet) {
    soup.triangles.push_back(t);
    soup.triangles.push_back({t[0], t[2], t[1]});
  }
  return soup;
}

std::int64_t filter_count(const tetmesh::PipelineResult& result, const std::string& key) {
  for (const tetmesh::StageStats& stage : result.stats.stages) {
    if (stage.name != "filter") continue;
    for (const auto& [name, value] : stage.counts) {
      if (name == key) return value;
    }
  }
  return -1;
}

/// The pipeline as the sheet fallbacks run it: no improvement.
tetmesh::PipelineResult tetrahedralize_unimproved(const TriangleSoup& soup) {
  tetmesh::PipelineOptions options;
  options.improve = false;
  return tetmesh::tetrahedralize(soup, options);
}

/// The result's tets, checked valid and closed.
check::TetReport valid_closed_report(const tetmesh::PipelineResult& result) {
  const check::TetReport report = check::check_tets(result.mesh);
  CHECK(report.valid());
  CHECK(report.boundary.closed());
  return report;
}

}  // namespace

TEST_CASE("thicken_sheets: a triangle becomes a closed outward prism within the half thickness",
          "[thicken]") {
  TriangleSoup triangle;
  triangle.positions = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {5, 5, 5}};
  triangle.triangles = {{0, 1, 2}, {0, 3, 3}};  // the second has no area: left out
  const double half = 0.25;
  const TriangleSoup prism = thicken_sheets(triangle, half);
  REQUIRE(prism.triangles.size() == 8);
  CHECK(std::abs(test::enclosed_volume(prism) - 1.0 * 2 * half) < 1e-12);
  TriangleSoup flat;
  flat.positions = triangle.positions;
  flat.triangles = {triangle.triangles[0]};
  CHECK(check::one_sided_distance(prism, flat).max <= half * (1 + 1e-12));
}

TEST_CASE("tetrahedralize: an input enclosing no volume gives its sheets thickened, not nothing",
          "[thicken][tetrahedralize][slow]") {
  const TriangleSoup sheets = crossing_doubled_sheets();
  const tetmesh::PipelineResult result = tetrahedralize_unimproved(sheets);
  CHECK(filter_count(result, "thickened_sheets") == 1);
  CHECK(filter_count(result, "closed_surface") == 1);
  const check::TetReport report = valid_closed_report(result);
  // Three crossing unit squares (area 2 each, as 4 triangles of 1/2), a
  // thickness of epsilon: where they cross the prisms overlap, so a little
  // less than 6 epsilon, never more.
  const double epsilon = result.parameters.epsilon;
  CHECK(report.volume > 0.8 * 6 * epsilon);
  CHECK(report.volume < 1.05 * 6 * epsilon);
  CHECK(check::one_sided_distance(result.tracked_surface, sheets).max <= epsilon);
}

TEST_CASE("fatten_sheets: slivers and points become solids at least twice the radius wide", "[thicken]") {
  TriangleSoup slivers;
  slivers.positions = {{0, 0, 0}, {1, 0, 0}, {1e3, 1e3, 1e3}, {3, 3, 3}};
  slivers.triangles = {{0, 1, 2}, {3, 3, 3}};  // a sliver, and a triangle that is a point
  const double radius = 0.5;
  const TriangleSoup fat = fatten_sheets(slivers, radius);
  // One prism (the point has no normal) and a box per distinct edge: 3 for
  // the sliver, 1 for the point (its three edges are one).
  REQUIRE(fat.triangles.size() == 8 + 4 * 12);
  // The pieces are closed and outward, so their volumes add up: the prism's,
  // and each box's (edge length + 2 radius) * (2 radius)^2.
  double volume = (slivers.positions[1] - slivers.positions[0])
                      .cross(slivers.positions[2] - slivers.positions[0])
                      .norm() *
                  radius;  // the area, times a thickness of 2 radius
  for (const auto& [u, v] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{0, 2}, std::pair{3, 3}})
    volume += ((slivers.positions[v] - slivers.positions[u]).norm() + 2 * radius) * 4 * radius * radius;
  CHECK(std::abs(test::enclosed_volume(fat) - volume) <
        1e-8 * volume);  // the volume sums cancel products of 1e9
  CHECK(check::one_sided_distance(fat, slivers).max <= std::sqrt(3.0) * radius * (1 + 1e-9));
}

TEST_CASE("tetrahedralize: sheets far thinner than epsilon are fattened when thickening leaves nothing",
          "[thicken][tetrahedralize]") {
  // The meshrepair fuzzer's find: a unit triangle and a sliver 1e25 long
  // make epsilon 1.7e22; the prisms, a unit wide, are flattened by
  // simplification and their corners merged by snapping.
  TriangleSoup sheets;
  sheets.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1e25, 1e25, 1e25}};
  sheets.triangles = {{0, 1, 2}, {0, 1, 3}};
  const tetmesh::PipelineResult result = tetrahedralize_unimproved(sheets);
  CHECK(filter_count(result, "thickened_sheets") == 1);
  CHECK(filter_count(result, "fattened_sheets") == 1);
  const check::TetReport report = valid_closed_report(result);
  const double epsilon = result.parameters.epsilon;
  CHECK(report.volume > 0);
  CHECK(check::one_sided_distance(result.tracked_surface, sheets).max <= 0.67 * epsilon);
}

TEST_CASE("cell_solid: the cells a triangle meets, as one closed solid", "[thicken]") {
  TriangleSoup triangle;
  triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.triangles = {{0, 1, 2}};
  const double cell = 0.5;
  const TriangleSoup solid = cell_solid(triangle, cell);
  // Cells are counted from the input's box, so only the layer above z = 0;
  // in the plane, the six cells of [0, 1.5]^2 that reach the triangle (two
  // at its corners (1, 0) and (0, 1), one at (0.5, 0.5) on its long edge):
  // a staircase whose outer squares are 24, two triangles each.
  CHECK(solid.triangles.size() == 48);
  CHECK(std::abs(test::enclosed_volume(solid) - 6 * cell * cell * cell) < 1e-12);
  CHECK(check::one_sided_distance(solid, triangle).max <= std::sqrt(3.0) * cell);
  CHECK(cell_solid(TriangleSoup{}, cell).triangles.empty());
}

TEST_CASE("tetrahedralize: an input a few epsilons across that encloses no volume is meshed as its cells",
          "[thicken][tetrahedralize]") {
  // The meshrepair fuzzer's finds: a few unit triangles and an unused vertex
  // far away (epsilon 17 here) made prisms 17 high and 1 wide, needles
  // crossing each other (3,000 to 10,000 cut points, up to 74 s in the
  // sanitizer build).
  TriangleSoup sheets;
  sheets.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1e4, 1e4, 1e4}};
  sheets.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}};
  const tetmesh::PipelineResult result = tetrahedralize_unimproved(sheets);
  CHECK(filter_count(result, "cell_solid") == 1);
  CHECK(filter_count(result, "thickened_sheets") == -1);
  const check::TetReport report = valid_closed_report(result);
  CHECK(report.volume > 0);
  CHECK(check::one_sided_distance(result.tracked_surface, sheets).max <= 0.54 * result.parameters.epsilon);
}
