// Refinement of the barrier tets of the closed-input filter (winding_filter.h).

#include "improve_local.h"

#include <mr/tetmesh/winding_filter.h>

#include <algorithm>
#include <array>
#include <map>
#include <tuple>
#include <vector>

namespace mr::tetmesh {
namespace {

using improve_detail::Workspace;

bool kept(const TetClassification& classes, Index t) { return t != kNoTet && classes.keep[t] != 0; }

// Sorted corners of a face, and whether it lies in the envelope: vertices
// do not move during the refinement, so an answer holds for later rounds.
using FaceInside = std::map<std::array<Index, 3>, bool>;

bool face_inside(const Mesh& mesh, std::array<Index, 3> f, const envelope::Envelope& envelope,
                 FaceInside& known) {
  std::sort(f.begin(), f.end());
  const auto [it, added] = known.try_emplace(f, false);
  if (added) {
    it->second = envelope.is_inside(mesh.position(f[0]).approx, mesh.position(f[1]).approx,
                                    mesh.position(f[2]).approx);
  }
  return it->second;
}

// Barrier tets on either side of a boundary face (kept against removed or
// hull) that is not tracked and leaves the envelope, in slot order. Counts
// all such faces in `outside`, whether or not a barrier tet is there to split.
std::vector<Index> tets_making_faces_outside(const Mesh& mesh, const TetClassification& classes,
                                             std::span<const char> barrier,
                                             const envelope::Envelope& envelope, FaceInside& known,
                                             std::size_t& outside) {
  std::vector<char> marked(mesh.tet_slots(), 0);
  outside = 0;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t) || !kept(classes, t)) continue;
    for (int k = 0; k < 4; ++k) {
      const Index n = mesh.neighbour(t, k);
      if (kept(classes, n) || mesh.is_surface_face(t, k)) continue;
      if (face_inside(mesh, mesh.face_vertices(t, k), envelope, known)) continue;
      ++outside;
      if (barrier[t] != 0) marked[t] = 1;
      if (n != kNoTet && barrier[n] != 0) marked[n] = 1;
    }
  }
  std::vector<Index> tets;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (marked[t] != 0) tets.push_back(t);
  }
  return tets;
}

// Splits the longest edge of tet t at its midpoint, or the next longest when
// that split is refused. Returns whether one was split.
bool split_longest_edge(Workspace& ws, Index t) {
  const Tet corners = ws.mesh.tet(t);
  struct Edge {
    double length;
    Index a, b;
  };
  std::vector<Edge> edges;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      const Index a = std::min(corners[i], corners[j]), b = std::max(corners[i], corners[j]);
      edges.push_back({(ws.mesh.position(a).approx - ws.mesh.position(b).approx).norm(), a, b});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    if (x.length != y.length) return x.length > y.length;
    return std::tie(x.a, x.b) < std::tie(y.a, y.b);
  });
  for (const Edge& e : edges) {
    const Vec3d middle = 0.5 * (ws.mesh.position(e.a).approx + ws.mesh.position(e.b).approx);
    if (improve_detail::try_split(ws, e.a, e.b, HybridPoint(middle), true) != kNoVertex) return true;
  }
  return false;
}

}  // namespace

TetClassification classify_with_refined_barrier(Mesh& mesh, const TriangleSoup& holes,
                                                const WindingNumberTree& tree, WindingRule rule,
                                                const envelope::Envelope& envelope,
                                                const BarrierRefinementOptions& options,
                                                BarrierRefinementStats& stats) {
  // Splits use neither the target length nor the stop energy.
  Workspace ws(mesh, &envelope, 1.0, 10.0);
  WindingCache winding;
  FaceInside known;
  for (stats.rounds = 0;; ++stats.rounds) {
    const std::vector<char> barrier = tets_near(mesh, holes);
    TetClassification classes = classify_regions(mesh, tree, rule, barrier, &winding);
    stats.barrier_tets = static_cast<std::size_t>(std::count(barrier.begin(), barrier.end(), 1));
    const std::vector<Index> to_split =
        tets_making_faces_outside(mesh, classes, barrier, envelope, known, stats.faces_outside);
    if (to_split.empty() || stats.rounds == options.max_rounds) return classes;
    std::size_t splits = 0;
    for (const Index t : to_split) {
      // An earlier split in this round may have replaced t.
      if (mesh.tet_alive(t) && split_longest_edge(ws, t)) ++splits;
    }
    stats.splits += splits;
    if (splits == 0) return classes;
  }
}

}  // namespace mr::tetmesh
