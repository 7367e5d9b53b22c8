#include "filter_preview.h"

#include "regions.h"

#include <mr/tetmesh/improve.h>
#include <mr/tetmesh/winding_filter.h>
#include <mr/winding_number/winding_number.h>

#include <algorithm>
#include <cmath>

namespace mr::tetmesh::detail {
namespace {

// Below it, a tet is removed whatever the rule (|w| > 1/2 or w > 1/2), with
// room for per-tet numbers asked again after improvement to move a little.
constexpr double kMargin = 0.25;

// Whether some rule keeps a tet of winding number w: the absolute one.
bool kept_by_some_rule(double w) { return is_inside(w, WindingRule::absolute); }

}  // namespace

FilterPreview preview_filter(const Mesh& mesh, const TriangleSoup& surface, std::span<const char> left_out) {
  std::vector<FaceRef> origins;
  const TriangleSoup tracked = tracked_surface(mesh, {}, surface, Multiplicity::as_chain, &origins);
  const std::size_t boundary_edges = unbalanced_edges(tracked).size();
  // The rule does not matter here: only the winding numbers are read.
  if (boundary_edges == 0)
    return {classify_regions(mesh, WindingNumberTree(tracked), WindingRule::absolute).winding, true};
  OpenSurfaceStats stats;
  return {open_tracked_winding(mesh, tracked, origins, boundary_edges, surface, left_out, stats), false};
}

DecisionFaces decision_faces(const Mesh& mesh, std::span<const double> winding) {
  const auto kept = [&](Index t) { return t != kNoTet && kept_by_some_rule(winding[t]); };
  DecisionFaces out;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (int f = 0; f < 4; ++f) {
      const Index u = mesh.neighbour(t, f);
      if ((u != kNoTet && u < t) || kept(t) == kept(u)) continue;
      ++(mesh.is_surface_face(t, f) ? out.tracked : out.untracked);
    }
  }
  return out;
}

std::vector<char> fates_from_winding(const Mesh& mesh, std::span<const double> winding, bool carried) {
  const auto removed = [&](Index t) {
    return carried ? !kept_by_some_rule(winding[t]) : std::abs(winding[t]) < kMargin;
  };
  // Removed tets with a corner on a kept one share the vertices whose moves
  // and collapses improve the kept tets.
  std::vector<char> touched(mesh.vertex_slots(), 0);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t) || removed(t)) continue;
    for (const Index v : mesh.tet(t)) touched[v] = 1;
  }
  std::vector<char> out(mesh.tet_slots(), kWritten);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t) || !removed(t)) continue;
    const Tet& c = mesh.tet(t);
    const bool beside = std::any_of(c.begin(), c.end(), [&](Index v) { return touched[v] != 0; });
    out[t] = beside ? kBesideWritten : kDropped;
  }
  return out;
}

}  // namespace mr::tetmesh::detail
