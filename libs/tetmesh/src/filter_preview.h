#pragma once
// What the filter (stage 6) will decide, foreseen before improvement
// (stage 5): improvement then spends its passes on the tets that are
// written, and carries the decision to the tets it makes.

#include <mr/core/triangle_soup.h>
#include <mr/tetmesh/mesh.h>

#include <span>
#include <vector>

namespace mr::tetmesh::detail {

struct FilterPreview {
  /// Per tet slot, the winding number the filter's decision rests on (0 for
  /// removed slots).
  std::vector<double> winding;
  /// The tracked surface is a cycle: `winding` is an integer per region,
  /// exactly what the filter decides, and improvement, which never moves a
  /// tet across a tracked face, cannot change it. Otherwise it is the
  /// filter's per-tet number (open_tracked_winding), which improvement
  /// changes by little as it moves tracked faces within the envelope.
  bool by_region = false;
};

FilterPreview preview_filter(const Mesh& mesh, const TriangleSoup& surface, std::span<const char> left_out);

/// Per tet slot, its TetFate (improve.h): kDropped or kBesideWritten (a
/// corner on a kWritten tet) for a tet the filter removes under any winding
/// rule, its winding number below 1/4 in magnitude; kWritten for the
/// others, removed slots included.
std::vector<char> fates_from_winding(const Mesh& mesh, std::span<const double> winding);

}  // namespace mr::tetmesh::detail
