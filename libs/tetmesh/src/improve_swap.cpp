// Swaps: 3-2 and 4-4 edge removal, 2-3 face removal. Each new tet is an old
// tet with one corner replaced, keeping a face of the cavity's boundary, so
// its orientation follows from the old one; the exact positivity test then
// decides whether the swap is geometrically valid. Swaps never remove a
// tracked face and are taken only when they lower the largest energy.

#include "improve_local.h"

#include <algorithm>

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

// The new tets of a 4-4 swap whose new edge joins ring[k] and ring[k + 2].
std::vector<Tet> four_four(const Mesh& mesh, const EdgeRing& r, int k, Index a, Index b) {
  const Tet& near = mesh.tet(r.tets[k]);
  const Tet& far = mesh.tet(r.tets[k + 2]);
  const Index xk = r.ring[k], xk2 = r.ring[k + 2];
  return {replaced(near, b, xk2), replaced(near, a, xk2), replaced(far, b, xk), replaced(far, a, xk)};
}

}  // namespace

int try_edge_swap(Workspace& ws, Index a, Index b, Index hint) {
  Mesh& mesh = ws.mesh;
  const std::vector<Index> tets = ws.edge_tets(a, b, hint);
  if (tets.size() != 3 && tets.size() != 4) return 0;
  if (edge_has_tracked_face(mesh, tets, a, b)) return 0;
  const EdgeRing ring = edge_ring(mesh, tets, a, b);
  if (ring.tets.empty()) return 0;

  const double old_max = max_energy_of(mesh, tets);
  std::vector<std::vector<Tet>> options;
  if (tets.size() == 3) {
    const Tet& t0 = mesh.tet(ring.tets[0]);
    options.push_back({replaced(t0, b, ring.ring[2]), replaced(t0, a, ring.ring[2])});
  } else {
    options.push_back(four_four(mesh, ring, 0, a, b));
    options.push_back(four_four(mesh, ring, 1, a, b));
  }
  int best = -1;
  double best_max = old_max;
  for (std::size_t i = 0; i < options.size(); ++i) {
    const double e = max_energy(mesh, options[i]);
    if (e < best_max && all_positive(mesh, options[i])) {
      best = int(i);
      best_max = e;
    }
  }
  if (best < 0) return 0;
  replace_tets(ws, ring.tets, options[best], same_faces);
  return tets.size() == 3 ? 32 : 44;
}

bool try_face_swap(Workspace& ws, Index t, int f) {
  Mesh& mesh = ws.mesh;
  const Index u = mesh.neighbour(t, f);
  if (u == kNoTet || mesh.is_surface_face(t, f)) return false;
  const int fu = mesh.face_towards(u, t);
  if (fu < 0) return false;
  const Index b = mesh.tet(u)[fu];
  std::vector<Tet> new_tets;
  for (const Index w : mesh.face_vertices(t, f)) new_tets.push_back(replaced(mesh.tet(t), w, b));
  const std::array<Index, 2> old_tets{t, u};
  if (max_energy(mesh, new_tets) >= max_energy_of(mesh, old_tets)) return false;
  if (!all_positive(mesh, new_tets)) return false;
  replace_tets(ws, old_tets, new_tets, same_faces);
  return true;
}

}  // namespace mr::tetmesh::improve_detail
