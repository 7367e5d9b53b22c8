#pragma once
// Stage 6 as the pipeline runs it: which tets are written, from the
// decision improvement carried or from the tracked surface improvement
// left (winding_filter.h has the classifications themselves).

#include <mr/core/triangle_soup.h>
#include <mr/envelope/envelope.h>
#include <mr/tetmesh/mesh.h>
#include <mr/tetmesh/options.h>
#include <mr/tetmesh/stats.h>
#include <mr/tetmesh/winding_filter.h>

#include <span>
#include <vector>

namespace mr::tetmesh::detail {

/// What improvement carried to the filter, per tet slot of the improved mesh.
struct CarriedDecision {
  /// The filter's winding number, decided before improvement by region
  /// (FilterPreview::by_region) or, on an open input, per tet; empty when
  /// the filter decides afterwards (a closed input whose tracked surface
  /// was no cycle, an open input whose decision changes much across open
  /// space, or rational points left to round).
  std::vector<double> winding;
  /// The TetFate (improve.h) improvement worked with; empty when it had none.
  std::vector<char> fate;
  /// `winding` was decided by region.
  bool by_region = false;
};

/// The filter's decision per live tet of `mesh`, whose tracked faces embed
/// the triangles of `surface` but those with left_out[i] != 0. Counts into
/// `timer` how it was decided. May split tets (classify_with_refined_barrier).
TetClassification filter_tets(Mesh& mesh, const TriangleSoup& surface, std::span<const char> left_out,
                              const CarriedDecision& carried, double epsilon,
                              const envelope::Envelope& envelope, WindingRule rule, StageTimer& timer);

}  // namespace mr::tetmesh::detail
