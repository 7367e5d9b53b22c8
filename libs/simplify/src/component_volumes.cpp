// Signed volumes of the closed components of the mesh being simplified, kept
// up to date by collapses and flips (see MeshState::collapse_keeps_volume).

#include "mesh_state.h"

#include <mr/core/union_find.h>

#include <cmath>

namespace mr::simplify {
namespace {

// Six times the signed volume of the tet (reference, corners).
double volume6(const Corners& c, const Vec3d& reference) {
  return (c[0] - reference).dot((c[1] - reference).cross(c[2] - reference));
}

}  // namespace

void MeshState::build_component_volumes() {
  UnionFind sets(mesh_.n_vertices());
  for (auto e : mesh_.edges())
    sets.unite(mesh_.from_vertex_handle(mesh_.halfedge_handle(e, 0)).idx(),
               mesh_.to_vertex_handle(mesh_.halfedge_handle(e, 0)).idx());
  std::vector<std::uint32_t> id(mesh_.n_vertices(), std::uint32_t(-1));
  component_.assign(mesh_.n_vertices(), 0);
  std::vector<Vec3d> reference;
  for (auto v : mesh_.vertices()) {
    const std::size_t root = sets.find(v.idx());
    if (id[root] == std::uint32_t(-1)) {
      id[root] = static_cast<std::uint32_t>(reference.size());
      reference.push_back(point(v));
    }
    component_[v.idx()] = id[root];
  }
  volume6_.assign(reference.size(), 0.0);
  closed_.assign(reference.size(), 1);
  for (auto h : mesh_.halfedges())
    if (mesh_.is_boundary(h)) closed_[component_[mesh_.from_vertex_handle(h).idx()]] = 0;
  for (auto f : mesh_.faces()) {
    const std::uint32_t c = component_[mesh_.fv_begin(f)->idx()];
    volume6_[c] += volume6(corners(f), reference[c]);
  }
  initial_volume6_ = volume6_;
}

// The change does not depend on the reference point: the old and the new
// faces bound the same loop. v1's position makes the removed faces vanish.
double MeshState::collapse_volume_change(TriMesh::HalfedgeHandle h) const {
  const Vec3d reference = point(mesh_.to_vertex_handle(h));
  double change = 0.0;
  for (auto f : mesh_.vf_range(mesh_.from_vertex_handle(h))) change -= volume6(corners(f), reference);
  for (const NewFace& face : faces_after_collapse(h)) change += volume6(face.corners, reference);
  return change;
}

double MeshState::flip_volume_change(TriMesh::EdgeHandle e) const {
  const Vec3d reference = point(mesh_.from_vertex_handle(mesh_.halfedge_handle(e, 0)));
  const std::vector<NewFace> after = faces_after_flip(e);
  return volume6(after[0].corners, reference) + volume6(after[1].corners, reference) -
         volume6(corners(mesh_.face_handle(mesh_.halfedge_handle(e, 0))), reference) -
         volume6(corners(mesh_.face_handle(mesh_.halfedge_handle(e, 1))), reference);
}

// A closed component keeps its sign (one given inside out, with negative
// volume, stays so) and at least half of the volume it started with: the
// envelope alone lets a solid thinner than epsilon (a sheet thickened to
// epsilon) be flattened to a tet of volume 1e-19, whose sign float32
// rounding then turns over.
bool MeshState::keeps_enough_volume(TriMesh::VertexHandle v, double change) const {
  const std::uint32_t c = component_[v.idx()];
  const double before = volume6_[c];
  if (!closed_[c] || before == 0.0) return true;
  const double after = before + change;
  const bool same_sign = before > 0.0 ? after > 0.0 : after < 0.0;
  return same_sign && std::abs(after) >= 0.5 * std::abs(initial_volume6_[c]);
}

bool MeshState::collapse_keeps_volume(TriMesh::HalfedgeHandle h) const {
  return keeps_enough_volume(mesh_.to_vertex_handle(h), collapse_volume_change(h));
}

bool MeshState::flip_keeps_volume(TriMesh::EdgeHandle e) const {
  return keeps_enough_volume(mesh_.from_vertex_handle(mesh_.halfedge_handle(e, 0)), flip_volume_change(e));
}

}  // namespace mr::simplify
