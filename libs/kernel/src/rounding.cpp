#include <mr/kernel/rounding.h>

#include <mr/core/errors.h>

#include <string>
#include <vector>

namespace mr {

std::array<Index, 3> opposite_face(const Tet& tet, int corner) {
  // Each row is an even permutation of the tet that brings `corner` first.
  switch (corner) {
    case 0:
      return {tet[1], tet[2], tet[3]};
    case 1:
      return {tet[0], tet[3], tet[2]};
    case 2:
      return {tet[3], tet[0], tet[1]};
    case 3:
      return {tet[2], tet[1], tet[0]};
    default:
      throw UsageError("opposite_face: corner must be 0..3, got " + std::to_string(corner));
  }
}

bool keeps_orientation(const Vec3d& rounded, std::span<const OppositeFace> faces) {
  const HybridPoint moved(rounded);
  for (const OppositeFace& face : faces) {
    if (orient3d(moved, *face[0], *face[1], *face[2]) <= 0) return false;
  }
  return true;
}

bool try_round(HybridPoint& point, std::span<const OppositeFace> faces) {
  if (!point.exact) return true;
  // approx is the nearest double position by the HybridPoint invariant.
  if (!keeps_orientation(point.approx, faces)) return false;
  point.exact.reset();
  return true;
}

bool try_round_vertex(std::span<HybridPoint> positions, Index vertex, std::span<const Tet> incident_tets) {
  if (vertex >= positions.size()) {
    throw UsageError("try_round_vertex: vertex " + std::to_string(vertex) + " out of range");
  }
  if (!positions[vertex].exact) return true;
  std::vector<OppositeFace> faces;
  faces.reserve(incident_tets.size());
  for (const Tet& tet : incident_tets) {
    int corner = -1;
    for (int k = 0; k < 4; ++k) {
      if (tet[k] >= positions.size()) throw UsageError("try_round_vertex: tet index out of range");
      if (tet[k] == vertex) corner = k;
    }
    if (corner < 0) throw UsageError("try_round_vertex: a tet does not contain the vertex");
    const std::array<Index, 3> others = opposite_face(tet, corner);
    faces.push_back({&positions[others[0]], &positions[others[1]], &positions[others[2]]});
  }
  return try_round(positions[vertex], faces);
}

}  // namespace mr
