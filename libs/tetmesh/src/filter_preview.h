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

/// Where the decision `winding` gives (kept by |w| > 1/2) changes between
/// two tets, or a tet and the hull: on tracked faces, or across open space
/// (caps over holes and gaps, untracked).
struct DecisionFaces {
  std::size_t tracked = 0;
  std::size_t untracked = 0;
  double untracked_share() const {
    const std::size_t all = tracked + untracked;
    return all == 0 ? 0.0 : double(untracked) / double(all);
  }
};
DecisionFaces decision_faces(const Mesh& mesh, std::span<const double> winding);

/// Per tet slot, its TetFate (improve.h): kDropped or kBesideWritten (a
/// corner on a kWritten tet) for a tet the filter removes under any winding
/// rule; kWritten for the others, removed slots included. A `carried`
/// decision is final: removed means a winding number of at most 1/2 in
/// magnitude. Otherwise the filter asks again after improvement, and
/// removed means below 1/4, with room for the per-tet numbers to move.
std::vector<char> fates_from_winding(const Mesh& mesh, std::span<const double> winding, bool carried);

}  // namespace mr::tetmesh::detail
