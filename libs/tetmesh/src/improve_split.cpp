// Edge split: every tet around edge (a, b) becomes two, sharing the new
// vertex m. Tracked faces on the edge are halved and both halves keep the ids.

#include "improve_local.h"

#include <algorithm>
#include <optional>

namespace mr::tetmesh::improve_detail {
namespace {

Tet replaced(Tet t, Index from, Index to) {
  std::replace(t.begin(), t.end(), from, to);
  return t;
}

// Faces of the new tets that contain m and a came from the face with b, and back.
ParentFaces split_parents(Index a, Index b, Index m) {
  return [=](const FaceKey& face, std::vector<FaceKey>& parents) {
    const bool has_m = std::find(face.begin(), face.end(), m) != face.end();
    if (!has_m) {
      parents.push_back(face);
      return;
    }
    const bool has_a = std::find(face.begin(), face.end(), a) != face.end();
    const bool has_b = std::find(face.begin(), face.end(), b) != face.end();
    if (!has_a && !has_b) return;  // the new face inside an old tet
    FaceKey parent = face;
    std::replace(parent.begin(), parent.end(), m, has_a ? b : a);
    parents.push_back(face_key(parent));
  };
}

}  // namespace

std::optional<SplitPlan> plan_split(const Workspace& ws, Index a, Index b, const HybridPoint& at,
                                    bool check_envelope, std::vector<Index> old_tets) {
  const Mesh& mesh = ws.mesh;
  SplitPlan plan;
  plan.a = a;
  plan.b = b;
  plan.at = at;
  plan.new_tets.reserve(old_tets.size() * 2);
  for (std::size_t i = 0; i < old_tets.size(); ++i) {
    plan.new_tets.push_back(replaced(mesh.tet(old_tets[i]), a, kNewVertex));
    plan.new_tets.push_back(replaced(mesh.tet(old_tets[i]), b, kNewVertex));
    plan.origin.insert(plan.origin.end(), {i, i});  // each old tet becomes two
  }
  const Override moved{kNewVertex, &at};
  if (!all_positive(mesh, plan.new_tets, moved)) return std::nullopt;

  std::vector<FaceCorners> halves;
  for (const TrackedFace& face : tracked_faces(mesh, old_tets)) {
    const FaceKey& k = face.key;
    if (std::find(k.begin(), k.end(), a) == k.end() || std::find(k.begin(), k.end(), b) == k.end()) continue;
    FaceCorners first = k, second = k;
    std::replace(first.begin(), first.end(), a, kNewVertex);
    std::replace(second.begin(), second.end(), b, kNewVertex);
    halves.push_back(first);
    halves.push_back(second);
  }
  if (check_envelope && !faces_inside(ws, halves, moved)) return std::nullopt;

  if (edge_on_hull(mesh, old_tets, a, b)) plan.flags |= kOnBox;
  if (mesh.has_flag(a, kLocked) && mesh.has_flag(b, kLocked)) plan.flags |= kLocked;
  if (mesh.has_flag(a, kOnBoundary) && mesh.has_flag(b, kOnBoundary) && halves.size() != 4) {
    plan.flags |= kOnBoundary;  // an open (or non-manifold) edge of the tracked surface
  }
  plan.old_tets = std::move(old_tets);
  return plan;
}

Index apply_split(Workspace& ws, SplitPlan plan) {
  Mesh& mesh = ws.mesh;
  const Index m = mesh.add_vertex(plan.at, plan.flags);
  const double size_a = plan.a < ws.sizing.size() ? ws.sizing[plan.a] : 1.0;
  const double size_b = plan.b < ws.sizing.size() ? ws.sizing[plan.b] : 1.0;
  ws.note_vertex(m, 0.5 * (size_a + size_b));
  for (Tet& t : plan.new_tets) std::replace(t.begin(), t.end(), kNewVertex, m);
  replace_tets(ws, plan.old_tets, plan.new_tets, split_parents(plan.a, plan.b, m), plan.origin);
  return m;
}

Index try_split(Workspace& ws, Index a, Index b, const HybridPoint& at, bool check_envelope, Index hint) {
  std::vector<Index> old_tets = ws.edge_tets(a, b, hint);
  if (old_tets.empty()) return kNoVertex;
  std::optional<SplitPlan> plan = plan_split(ws, a, b, at, check_envelope, std::move(old_tets));
  return plan ? apply_split(ws, std::move(*plan)) : kNoVertex;
}

}  // namespace mr::tetmesh::improve_detail

namespace mr::tetmesh {

Index split_edge(Mesh& mesh, Index a, Index b, const HybridPoint& position) {
  if (!mesh.vertex_alive(a) || !mesh.vertex_alive(b) || a == b) return kNoVertex;
  improve_detail::Workspace ws(mesh, nullptr, 1.0, 10.0);
  return improve_detail::try_split(ws, a, b, position, false);
}

}  // namespace mr::tetmesh
