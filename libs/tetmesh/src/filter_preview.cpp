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
// room for the per-tet numbers to move a little during improvement.
constexpr double kMargin = 0.25;

}  // namespace

FilterPreview preview_filter(const Mesh& mesh, const TriangleSoup& surface, std::span<const char> left_out) {
  const TriangleSoup tracked = tracked_surface(mesh, {}, surface, Multiplicity::as_chain);
  // The rule does not matter here: only the winding numbers are read.
  const WindingRule any = WindingRule::absolute;
  if (unbalanced_edges(tracked).empty())
    return {classify_regions(mesh, WindingNumberTree(tracked), any).winding, true};
  const std::vector<double> offsets = tracked_surface_offsets(mesh, surface);
  return {classify_tets_near_input(mesh, WindingNumberTree(tracked), surface, left_out, offsets, any).winding,
          false};
}

std::vector<char> fates_from_winding(const Mesh& mesh, std::span<const double> winding) {
  // Removed tets with a corner on a kept one share the vertices whose moves
  // and collapses improve the kept tets.
  std::vector<char> touched(mesh.vertex_slots(), 0);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t) || std::abs(winding[t]) < kMargin) continue;
    for (const Index v : mesh.tet(t)) touched[v] = 1;
  }
  std::vector<char> out(mesh.tet_slots(), kWritten);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t) || std::abs(winding[t]) >= kMargin) continue;
    const Tet& c = mesh.tet(t);
    const bool beside = std::any_of(c.begin(), c.end(), [&](Index v) { return touched[v] != 0; });
    out[t] = beside ? kBesideWritten : kDropped;
  }
  return out;
}

}  // namespace mr::tetmesh::detail
