// Open boundaries (seed section 3.4): improvement may slide a boundary
// vertex along its boundary line, but the line must stay near the input's
// boundary, not only near its surface. A flat disk shows the difference:
// a chord of its rim stays on the disk (inside the surface envelope) but
// cuts into it, away from the rim.

#include <mr/tetmesh/tetrahedralize.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

using namespace mr;

namespace {

TriangleSoup flat_disk(int segments) {
  TriangleSoup disk;
  disk.positions.push_back({0, 0, 0});
  for (int i = 0; i < segments; ++i) {
    const double angle = 2 * std::numbers::pi * i / segments;
    disk.positions.push_back({std::cos(angle), std::sin(angle), 0});
  }
  for (int i = 0; i < segments; ++i) {
    disk.triangles.push_back({0, Index(1 + i), Index(1 + (i + 1) % segments)});
  }
  return disk;
}

double segment_distance(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Edges used by exactly one triangle (vertices compared by index).
std::vector<std::array<Index, 2>> open_edges(const TriangleSoup& soup) {
  std::map<std::array<Index, 2>, int> uses;
  for (const Triangle& t : soup.triangles) {
    for (int i = 0; i < 3; ++i) ++uses[{std::min(t[i], t[(i + 1) % 3]), std::max(t[i], t[(i + 1) % 3])}];
  }
  std::vector<std::array<Index, 2>> out;
  for (const auto& [edge, count] : uses) {
    if (count == 1) out.push_back(edge);
  }
  return out;
}

// Largest distance from points sampled on the open edges of `surface` to
// the open edges of `input`.
double open_boundary_distance(const TriangleSoup& surface, const TriangleSoup& input) {
  const auto input_edges = open_edges(input);
  double worst = 0;
  for (const auto& [a, b] : open_edges(surface)) {
    for (int k = 0; k <= 16; ++k) {
      const Vec3d p = surface.positions[a] + (k / 16.0) * (surface.positions[b] - surface.positions[a]);
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& [c, d] : input_edges) {
        nearest = std::min(nearest, segment_distance(p, input.positions[c], input.positions[d]));
      }
      worst = std::max(worst, nearest);
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("tetrahedralize: open boundaries stay near the input's boundary through improvement",
          "[tetrahedralize][open-boundary][slow]") {
  const TriangleSoup disk = flat_disk(64);
  tetmesh::PipelineOptions options;
  options.filter = false;  // a disk encloses nothing: look at every tracked face
  options.tetrahedralize.skip_simplify = true;
  // Long target edges: collapses along the rim would leave chords far
  // longer than its segments (sagitta of a 0.4 chord: 0.02, epsilon 0.0028).
  options.tetrahedralize.edge_length_abs = 0.5;
  const tetmesh::PipelineResult result = tetmesh::tetrahedralize(disk, options);
  REQUIRE(!open_edges(result.tracked_surface).empty());
  CHECK(open_boundary_distance(result.tracked_surface, disk) <= result.parameters.epsilon);
}
