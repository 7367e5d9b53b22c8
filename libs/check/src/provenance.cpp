#include <mr/check/provenance.h>

#include <mr/spatial/aabb_tree.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <unordered_map>

namespace mr::check {
namespace {

// Three positions in lexicographic order: a triangle's key whatever its
// orientation and first corner.
using CornerSet = std::array<std::array<double, 3>, 3>;

CornerSet corner_set(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  CornerSet set{{{a.x(), a.y(), a.z()}, {b.x(), b.y(), b.z()}, {c.x(), c.y(), c.z()}}};
  for (auto& p : set)
    for (double& x : p) x += 0.0;  // -0 and +0 are one position
  std::sort(set.begin(), set.end());
  return set;
}

struct CornerSetHash {
  std::size_t operator()(const CornerSet& set) const {
    std::size_t h = 0;
    for (const auto& p : set)
      for (double x : p) h = h * 0x9E3779B97F4A7C15ull + std::bit_cast<std::uint64_t>(x);
    return h ^ (h >> 29);
  }
};

// Input triangles by their corners on the grid; the first of equal ones.
std::unordered_map<CornerSet, std::int64_t, CornerSetHash> input_by_corners(const TriangleSoup& input,
                                                                            const CoordinateGrid& grid) {
  std::unordered_map<CornerSet, std::int64_t, CornerSetHash> by_corners;
  by_corners.reserve(input.triangles.size());
  for (std::size_t f = 0; f < input.triangles.size(); ++f) {
    const std::array<Vec3d, 3> p = input.corners(f);
    by_corners.emplace(corner_set(grid.nearest(p[0]), grid.nearest(p[1]), grid.nearest(p[2])),
                       static_cast<std::int64_t>(f));
  }
  return by_corners;
}

}  // namespace

FaceProvenance face_provenance(const TriangleSoup& output, const TriangleSoup& input,
                               const CoordinateGrid& grid, double epsilon) {
  const auto by_corners = input_by_corners(input, grid);
  const spatial::AabbTree tree(input);
  FaceProvenance provenance;
  provenance.input_face.assign(output.triangles.size(), -1);
  provenance.source.assign(output.triangles.size(), FaceSource::filled);
  tbb::parallel_for(std::size_t(0), output.triangles.size(), [&](std::size_t f) {
    const std::array<Vec3d, 3> p = output.corners(f);
    if (const auto it = by_corners.find(corner_set(p[0], p[1], p[2])); it != by_corners.end()) {
      provenance.input_face[f] = it->second;
      provenance.source[f] = FaceSource::kept;
      return;
    }
    const spatial::ClosestHit hit = tree.closest_within((p[0] + p[1] + p[2]) / 3.0, epsilon);
    if (!hit.found()) return;
    provenance.input_face[f] = hit.triangle;
    provenance.source[f] = FaceSource::recut;
  });
  return provenance;
}

double ProvenanceSummary::kept_area_share() const {
  const double total = kept_area + recut_area + filled_area;
  return total > 0.0 ? kept_area / total : 0.0;
}

ProvenanceSummary summarize_provenance(const FaceProvenance& provenance, const TriangleSoup& output) {
  ProvenanceSummary summary;
  std::vector<std::int64_t> kept;
  for (std::size_t f = 0; f < output.triangles.size(); ++f) {
    const std::array<Vec3d, 3> p = output.corners(f);
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    switch (provenance.source[f]) {
      case FaceSource::kept:
        ++summary.kept_faces, summary.kept_area += area;
        kept.push_back(provenance.input_face[f]);
        break;
      case FaceSource::recut:
        ++summary.recut_faces, summary.recut_area += area;
        break;
      case FaceSource::filled:
        ++summary.filled_faces, summary.filled_area += area;
        break;
    }
  }
  std::sort(kept.begin(), kept.end());
  summary.input_triangles_kept =
      static_cast<std::size_t>(std::unique(kept.begin(), kept.end()) - kept.begin());
  return summary;
}

}  // namespace mr::check
