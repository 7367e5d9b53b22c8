// Swaps: edge removal (the 3 to 7 tets around an edge; 3-2 and 4-4 are its
// smallest cases) and 2-3 face removal. Each new tet is an old tet with
// corners renamed, keeping a face of the cavity's boundary, so its
// orientation follows from the old one; the exact positivity test then
// decides whether the swap is geometrically valid. Swaps never remove a
// tracked face, never merge tets the carried filter decision tells apart,
// and are taken only when they lower the largest energy.

#include "improve_local.h"

#include <mr/tetmesh/incidence.h>

#include <algorithm>
#include <limits>
#include <optional>

namespace mr::tetmesh::improve_detail {
namespace {

Tet replaced(Tet t, Index from, Index to) {
  std::replace(t.begin(), t.end(), from, to);
  return t;
}

void same_faces(const FaceKey& face, std::vector<FaceKey>& parents) { parents.push_back(face); }

// Tets around the interior edge (a, b) in ring order: tet i has corners a, b,
// ring[i], ring[i + 1]. Empty when the ring is not closed.
struct EdgeRing {
  std::vector<Index> tets;
  std::vector<Index> ring;
};

EdgeRing edge_ring(const Mesh& mesh, std::span<const Index> tets, Index a, Index b) {
  EdgeRing out;
  if (tets.empty()) return out;
  const Index first = tets[0];
  std::array<Index, 2> others{};
  int k = 0;
  for (const Index w : mesh.tet(first)) {
    if (w != a && w != b) others[k++] = w;
  }
  Index behind = others[0], shared = others[1], current = first;
  out.tets.push_back(first);
  out.ring = {behind, shared};
  for (std::size_t step = 0; step < tets.size(); ++step) {
    const Index next = mesh.neighbour(current, mesh.corner_of(current, behind));
    if (next == kNoTet) return {};
    if (next == first) break;
    Index fresh = kNoVertex;
    for (const Index w : mesh.tet(next)) {
      if (w != a && w != b && w != shared) fresh = w;
    }
    out.tets.push_back(next);
    out.ring.push_back(fresh);
    behind = shared;
    shared = fresh;
    current = next;
  }
  if (out.tets.size() != tets.size()) return {};
  out.ring.pop_back();  // the walk came back to ring[0]
  return out;
}

bool edge_has_tracked_face(const Mesh& mesh, std::span<const Index> tets, Index a, Index b) {
  for (const Index t : tets) {
    for (int f = 0; f < 4; ++f) {
      const Index opposite = mesh.tet(t)[f];
      if (opposite != a && opposite != b && mesh.is_surface_face(t, f)) return true;
    }
  }
  return false;
}

// Edge removal (Shewchuk, "Two Discrete Optimization Algorithms for the
// Topological Improvement of Tetrahedral Meshes"): the n tets around edge
// (a, b) are replaced by two tets, one with a and one with b, on each
// triangle of a triangulation of the ring polygon. Among the triangulations
// the one with the smallest largest energy is found by dynamic programming
// over sub-polygons (Klincsek), O(n^3) for the ring's n <= kMaxRing.
constexpr int kMaxRing = 7;

class RingTriangulation {
 public:
  RingTriangulation(const Mesh& mesh, const EdgeRing& r, Index a, Index b)
      : mesh_(mesh), ring_(r.ring), a_(a), b_(b), n_(int(r.ring.size())) {
    // The first tet, positive, has corners a, b, ring[0], ring[1]: a tet of
    // the new set is it with ring[0], ring[1] and one of a, b renamed, which
    // keeps the orientation because triangles in ring order turn as the ring.
    first_ = mesh.tet(r.tets[0]);
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j < n_; ++j) cost_[i][j] = kUnknown;
    }
  }

  /// The largest energy of the best triangulation, and its tets.
  double solve(std::vector<Tet>& tets) {
    const double best = best_between(0, n_ - 1);
    collect(0, n_ - 1, tets);
    return best;
  }

 private:
  static constexpr double kUnknown = -1.0;

  // The two tets on triangle (ring[i], ring[j], ring[k]), i < j < k.
  std::array<Tet, 2> tets_on(int i, int j, int k) const {
    const Index ri = ring_[i], rj = ring_[j], rk = ring_[k], r0 = ring_[0], r1 = ring_[1];
    std::array<Tet, 2> out{first_, first_};
    for (Index& w : out[0]) w = w == b_ ? rk : w == r0 ? ri : w == r1 ? rj : w;
    for (Index& w : out[1]) w = w == a_ ? rk : w == r0 ? ri : w == r1 ? rj : w;
    return out;
  }

  double triangle_cost(int i, int j, int k) const {
    const std::array<Tet, 2> tets = tets_on(i, j, k);
    return max_energy(mesh_, tets);
  }

  // Best largest energy over triangulations of the sub-polygon i..j.
  double best_between(int i, int j) {
    if (j - i < 2) return 0.0;
    if (cost_[i][j] != kUnknown) return cost_[i][j];
    double best = std::numeric_limits<double>::infinity();
    int split = -1;
    for (int k = i + 1; k < j; ++k) {
      const double c = std::max({triangle_cost(i, k, j), best_between(i, k), best_between(k, j)});
      if (split < 0 || c < best) {
        best = c;
        split = k;
      }
    }
    cost_[i][j] = best;
    split_[i][j] = split;
    return best;
  }

  void collect(int i, int j, std::vector<Tet>& tets) const {
    if (j - i < 2) return;
    const int k = split_[i][j];
    for (const Tet& t : tets_on(i, k, j)) tets.push_back(t);
    collect(i, k, tets);
    collect(k, j, tets);
  }

  const Mesh& mesh_;
  const std::vector<Index>& ring_;
  Index a_, b_;
  int n_;
  Tet first_{};
  double cost_[kMaxRing][kMaxRing];
  int split_[kMaxRing][kMaxRing] = {};
};

}  // namespace

std::optional<SwapPlan> plan_edge_swap(const Workspace& ws, Index a, Index b, Index hint) {
  const Mesh& mesh = ws.mesh;
  const std::vector<Index> tets = tets_around_edge(mesh, a, b, hint);
  if (tets.size() < 3 || tets.size() > std::size_t(kMaxRing)) return std::nullopt;
  if (edge_has_tracked_face(mesh, tets, a, b) || ws.mixes_decisions(tets)) return std::nullopt;
  const EdgeRing ring = edge_ring(mesh, tets, a, b);
  if (ring.tets.empty()) return std::nullopt;

  const double old_max = max_energy_of(mesh, tets);
  SwapPlan plan;
  const double new_max = RingTriangulation(mesh, ring, a, b).solve(plan.new_tets);
  if (!(new_max < old_max) || !all_positive(mesh, plan.new_tets)) return std::nullopt;
  plan.old_tets = ring.tets;
  plan.kind = int(tets.size());
  return plan;
}

std::optional<SwapPlan> plan_face_swap(const Workspace& ws, Index t, int f) {
  const Mesh& mesh = ws.mesh;
  const Index u = mesh.neighbour(t, f);
  if (u == kNoTet || mesh.is_surface_face(t, f)) return std::nullopt;
  const int fu = mesh.face_towards(u, t);
  if (fu < 0) return std::nullopt;
  const Index b = mesh.tet(u)[fu];
  SwapPlan plan;
  for (const Index w : mesh.face_vertices(t, f)) plan.new_tets.push_back(replaced(mesh.tet(t), w, b));
  plan.old_tets = {t, u};
  if (ws.mixes_decisions(plan.old_tets)) return std::nullopt;
  if (max_energy(mesh, plan.new_tets) >= max_energy_of(mesh, plan.old_tets)) return std::nullopt;
  if (!all_positive(mesh, plan.new_tets)) return std::nullopt;
  plan.kind = 2;
  return plan;
}

std::optional<SwapPlan> plan_tet_swap(const Workspace& ws, Index t) {
  const Tet c = ws.mesh.tet(t);
  for (int x = 0; x < 4; ++x) {
    for (int y = x + 1; y < 4; ++y) {
      if (std::optional<SwapPlan> plan = plan_edge_swap(ws, c[x], c[y], t)) return plan;
    }
  }
  for (int f = 0; f < 4; ++f) {
    if (std::optional<SwapPlan> plan = plan_face_swap(ws, t, f)) return plan;
  }
  return std::nullopt;
}

void apply_swap(Workspace& ws, const SwapPlan& plan) {
  replace_tets(ws, plan.old_tets, plan.new_tets, same_faces);
}

}  // namespace mr::tetmesh::improve_detail
