// The checks every operation passes before it is applied (see mesh_state.h).

#include "mesh_state.h"

#include <mr/kernel/intersections.h>
#include <mr/kernel/predicates.h>
#include <mr/spatial/triangle_distance.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mr::simplify {
namespace {

Vec3d normal_of(const Corners& c) { return (c[1] - c[0]).cross(c[2] - c[0]); }

double smallest_angle(const Corners& c) {
  double smallest = std::numbers::pi;
  for (int i = 0; i < 3; ++i) {
    const Vec3d u = c[(i + 1) % 3] - c[i];
    const Vec3d w = c[(i + 2) % 3] - c[i];
    smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)));
  }
  return smallest;
}

// Every point of `points` lies exactly in the plane of `reference`.
bool coplanar(const Corners& reference, const std::vector<Vec3d>& points) {
  for (const Vec3d& p : points)
    if (orient3d(reference[0], reference[1], reference[2], p) != 0) return false;
  return true;
}

// Exact orientation of a face within the common plane, seen along `axis`.
int planar_orientation(const Corners& c, int axis) { return orient2d_projected(c[0], c[1], c[2], axis); }

// True when the old faces and the new faces lie in one plane (exactly), none
// is folded (all have the same exact orientation), and the new faces tile a
// region the old faces tiled. Then every new face lies in the old faces,
// which are inside the envelope (input faces, or faces checked when they were
// made), so the costly sampled test can be skipped. The caller guarantees
// that old and new faces cover the same polygon when none is folded.
bool new_faces_within_old(const std::vector<Corners>& old_faces, const std::vector<Corners>& new_faces) {
  const Corners* reference = nullptr;
  for (const Corners& c : old_faces)
    if (!collinear(c[0], c[1], c[2])) {
      reference = &c;
      break;
    }
  if (!reference) return false;
  std::vector<Vec3d> points;
  for (const Corners& c : old_faces) points.insert(points.end(), c.begin(), c.end());
  if (!coplanar(*reference, points)) return false;
  const int axis = dominant_axis(normal_of(*reference));
  const int sign = planar_orientation(*reference, axis);
  if (sign == 0) return false;
  for (const auto* faces : {&old_faces, &new_faces})
    for (const Corners& c : *faces)
      if (planar_orientation(c, axis) != sign) return false;
  return true;
}

}  // namespace

// Faces around v0 except the one or two that vanish, with v0 moved onto v1.
std::vector<MeshState::NewFace> MeshState::faces_after_collapse(TriMesh::HalfedgeHandle h) const {
  const auto v0 = mesh_.from_vertex_handle(h);
  const auto v1 = mesh_.to_vertex_handle(h);
  const auto gone_left = mesh_.face_handle(h);
  const auto gone_right = mesh_.opposite_face_handle(h);
  std::vector<NewFace> faces;
  for (auto f : mesh_.vf_range(v0)) {
    if (f == gone_left || f == gone_right) continue;
    NewFace face;
    int k = 0;
    for (auto v : mesh_.fv_range(f)) face.corners[k++] = point(v == v0 ? v1 : v);
    face.old_normal = normal_of(corners(f));
    faces.push_back(face);
  }
  return faces;
}

// OpenMesh's TriConnectivity::is_collapse_ok without its vertex tags, so
// that many threads can ask at once: the collapse must not glue two boundary
// edges of a face, pinch an interior edge between boundary vertices, or
// identify any common neighbour of v0 and v1 other than the two opposite
// vertices (the link condition).
bool MeshState::link_condition_holds(TriMesh::HalfedgeHandle h) const {
  const auto o = mesh_.opposite_halfedge_handle(h);
  const auto v0 = mesh_.from_vertex_handle(h);
  const auto v1 = mesh_.to_vertex_handle(h);
  if (mesh_.status(v0).deleted() || mesh_.status(v1).deleted()) return false;
  auto opposite_vertex = [&](TriMesh::HalfedgeHandle side, TriMesh::VertexHandle& apex) {
    if (mesh_.is_boundary(side)) return true;
    const auto h1 = mesh_.next_halfedge_handle(side);
    const auto h2 = mesh_.next_halfedge_handle(h1);
    apex = mesh_.to_vertex_handle(h1);
    return !(mesh_.is_boundary(mesh_.opposite_halfedge_handle(h1)) &&
             mesh_.is_boundary(mesh_.opposite_halfedge_handle(h2)));
  };
  TriMesh::VertexHandle vl;
  TriMesh::VertexHandle vr;
  if (!opposite_vertex(h, vl) || !opposite_vertex(o, vr)) return false;
  if (vl == vr) return false;
  if (mesh_.is_boundary(v0) && mesh_.is_boundary(v1) && !mesh_.is_boundary(h) && !mesh_.is_boundary(o))
    return false;
  std::vector<int> ring1;
  for (auto v : mesh_.vv_range(v1)) ring1.push_back(v.idx());
  for (auto v : mesh_.vv_range(v0)) {
    if (v == vl || v == vr) continue;
    if (std::find(ring1.begin(), ring1.end(), v.idx()) != ring1.end()) return false;
  }
  return true;
}

// A boundary vertex may only slide along its boundary edge, and the new
// boundary edge must stay in the envelope of the input's boundary curve and
// pass within epsilon of the vertex it removes.
bool MeshState::boundary_curve_kept(TriMesh::HalfedgeHandle h) const {
  const auto v0 = mesh_.from_vertex_handle(h);
  if (!mesh_.is_boundary(v0)) return true;
  if (!mesh_.is_boundary(mesh_.edge_handle(h)) || !boundary_envelope_) return false;
  const auto v1 = mesh_.to_vertex_handle(h);
  const auto out = mesh_.halfedge_handle(v0);  // a boundary vertex's is its outgoing boundary halfedge
  const auto in = mesh_.prev_halfedge_handle(out);
  TriMesh::VertexHandle other;
  if (mesh_.to_vertex_handle(out) == v1)
    other = mesh_.from_vertex_handle(in);
  else if (mesh_.from_vertex_handle(in) == v1)
    other = mesh_.to_vertex_handle(out);
  else
    return false;
  if (other == v1) return false;
  const Vec3d a = point(other);
  const Vec3d b = point(v1);
  if (spatial::closest_on_segment(point(v0), a, b).squared_distance >
      tolerances_.epsilon * tolerances_.epsilon)
    return false;
  return boundary_envelope_->is_inside(a, b);
}

bool MeshState::shapes_acceptable(const std::vector<NewFace>& faces) const {
  const double cos_max = tolerances_.cos_max_normal_deviation;
  for (const NewFace& face : faces) {
    const Corners& c = face.corners;
    if (collinear(c[0], c[1], c[2])) return false;
    const Vec3d n = normal_of(c);
    const double old_length = face.old_normal.norm();
    if (old_length > 0.0 && !(n.dot(face.old_normal) >= cos_max * n.norm() * old_length)) return false;
  }
  return true;
}

std::size_t MeshState::SortedCornersHash::operator()(const SortedCorners& key) const {
  std::size_t h = 0;
  for (double x : key) h = (h ^ std::hash<double>{}(x)) * 0x100000001b3ull;
  return h;
}

// The corners in lexicographic order, so that a triangle met in any rotation
// or orientation is tested (and stored) the same way.
MeshState::SortedCorners MeshState::sorted_corners(const Corners& c) { return sorted_corner_coordinates(c); }

Corners MeshState::corners_of(const SortedCorners& key) {
  return {Vec3d(key[0], key[1], key[2]), Vec3d(key[3], key[4], key[5]), Vec3d(key[6], key[7], key[8])};
}

// Most refusals are decided by a few points: the centroid and the edge
// midpoints. A triangle the full test accepts has all its points within the
// limit, so a refusal here is the full test's verdict too.
bool MeshState::quick_envelope_refusal(const Corners& c) const {
  for (const Vec3d& p : {Vec3d((c[0] + c[1] + c[2]) / 3.0), Vec3d(0.5 * (c[0] + c[1])),
                         Vec3d(0.5 * (c[1] + c[2])), Vec3d(0.5 * (c[2] + c[0]))})
    if (!envelope_->is_inside(p)) return true;
  return false;
}

// The sampled test is conservative (it may refuse faces inside); a refusal
// is asked again with the finer stage-2 sampling, closer to epsilon.
bool MeshState::full_envelope_test(const Corners& c) const {
  return envelope_->is_inside(c[0], c[1], c[2]) || fine_envelope_->is_inside(c[0], c[1], c[2]);
}

std::optional<bool> MeshState::known_envelope_verdict(const SortedCorners& key) const {
  if (const auto known = envelope_verdicts_.find(key); known != envelope_verdicts_.end())
    return known->second;
  if (const auto known = older_envelope_verdicts_.find(key); known != older_envelope_verdicts_.end())
    return known->second;
  return std::nullopt;
}

void MeshState::bound_caches() {
  // About 120 bytes an entry: at most two generations of 2^19, some 130 MB.
  constexpr std::size_t kVerdictsPerGeneration = std::size_t(1) << 19;
  if (envelope_verdicts_.size() < kVerdictsPerGeneration) return;
  older_envelope_verdicts_.swap(envelope_verdicts_);
  envelope_verdicts_.clear();
}

bool MeshState::inside_envelope(const std::vector<NewFace>& faces) const {
  std::vector<SortedCorners> unknown;
  for (const NewFace& face : faces) {
    const SortedCorners key = sorted_corners(face.corners);
    if (const std::optional<bool> known = known_envelope_verdict(key)) {
      if (!*known) return false;
    } else if (quick_envelope_refusal(corners_of(key))) {
      envelope_verdicts_.emplace(key, false);
      return false;
    } else {
      unknown.push_back(key);
    }
  }
  for (const SortedCorners& key : unknown) {
    const bool inside = full_envelope_test(corners_of(key));
    envelope_verdicts_.emplace(key, inside);
    if (!inside) return false;
  }
  return true;
}

bool MeshState::collapse_passes_local_checks(TriMesh::HalfedgeHandle h) const {
  if (!is_collapse_candidate(h)) return false;
  if (!link_condition_holds(h)) return false;
  if (!boundary_curve_kept(h)) return false;
  const std::vector<NewFace> faces = faces_after_collapse(h);
  if (!shapes_acceptable(faces)) return false;
  // In the plane, the new fan tiles the old fan's polygon: no point moves
  // away from the surface.
  if (collapse_stays_in_plane(h, faces)) return true;
  return inside_envelope(faces) && collapse_keeps_carried_points(h, faces);
}

// The collapse replaces the fan of v0 by a fan of v1 over the same polygon:
// for an interior v0 always, for a boundary v0 when the boundary is straight
// there (its neighbours on the boundary and v0 exactly collinear).
bool MeshState::collapse_stays_in_plane(TriMesh::HalfedgeHandle h, const std::vector<NewFace>& faces) const {
  const auto v0 = mesh_.from_vertex_handle(h);
  if (mesh_.is_boundary(v0)) {
    const auto out = mesh_.halfedge_handle(v0);
    const auto in = mesh_.prev_halfedge_handle(out);
    if (!collinear(point(mesh_.from_vertex_handle(in)), point(v0), point(mesh_.to_vertex_handle(out))))
      return false;
  }
  std::vector<Corners> old_faces;
  for (auto f : mesh_.vf_range(v0)) old_faces.push_back(corners(f));
  std::vector<Corners> new_faces;
  for (const NewFace& face : faces) new_faces.push_back(face.corners);
  return new_faces_within_old(old_faces, new_faces);
}

namespace {

Eigen::AlignedBox3d box_of(const Corners& c) {
  Eigen::AlignedBox3d box(c[0]);
  return box.extend(c[1]).extend(c[2]);
}

}  // namespace

// New faces may not cross each other. A face of the rest of the surface may
// be crossed by at most as many new faces as old faces crossed it: on a soup
// that already intersects itself (CAD booleans, overlapping parts) the faces
// around an existing crossing can still be simplified, while no face that
// was apart from the region gets crossed, and no pair count grows.
//
// The grid is asked once for the box around all new faces (they share a
// corner, so their boxes mostly overlap; one query per face took half of
// openscad-nonmanifold-crash's clean-up), then each candidate is tested
// against the new faces whose box it meets.
template <class Replaced>
bool MeshState::faces_apart(const std::vector<NewFace>& faces, const std::vector<Corners>& old_faces,
                            Replaced&& replaced) const {
  const auto crosses = [](const Corners& a, const Corners& b) {
    return intersect_triangles(a[0], a[1], a[2], b[0], b[1], b[2]).improper();
  };
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (std::size_t j = i + 1; j < faces.size(); ++j)
      if (crosses(faces[i].corners, faces[j].corners)) return false;
  if (faces.empty()) return true;
  // Closed boxes that do not meet hold triangles that do not meet: an exact
  // test on the doubles, cheaper than the orientation tests it spares.
  std::vector<Eigen::AlignedBox3d> boxes;
  std::vector<PlaneSideFilter> planes;
  Eigen::AlignedBox3d around;
  for (const NewFace& face : faces) {
    around.extend(boxes.emplace_back(box_of(face.corners)));
    planes.emplace_back(face.corners[0], face.corners[1], face.corners[2]);
  }
  std::vector<std::uint32_t> candidates;
  grid_.query_unordered(around.min(), around.max(), candidates);
  const auto n_mesh_faces = static_cast<std::uint32_t>(mesh_.n_faces());
  for (std::uint32_t id : candidates) {
    Corners b;
    if (id >= n_mesh_faces) {
      b = kept_aside_[id - n_mesh_faces];
    } else {
      const TriMesh::FaceHandle f(static_cast<int>(id));
      if (mesh_.status(f).deleted() || replaced(f)) continue;
      b = corners(f);
    }
    const Eigen::AlignedBox3d box = box_of(b);
    std::size_t crossings = 0;
    bool checked_collinear = false;
    for (std::size_t i = 0; i < faces.size(); ++i) {
      // Most faces in the box are wholly on one side of the new face's plane
      // (long CAD slivers: 4 in 5 on manifold/Generic_Twin), but for the
      // corners they share with it (the faces around the collapse).
      if (!boxes[i].intersects(box) || certainly_apart_but_shared(planes[i], faces[i].corners, b)) continue;
      // As check_surface: degenerate faces are not counted.
      if (!checked_collinear && collinear(b[0], b[1], b[2])) break;
      checked_collinear = true;
      crossings += crosses(faces[i].corners, b);
    }
    if (crossings == 0) continue;
    const auto crossed_before =
        static_cast<std::size_t>(std::count_if(old_faces.begin(), old_faces.end(), [&](const Corners& old) {
          return !collinear(old[0], old[1], old[2]) && crosses(old, b);
        }));
    if (crossings > crossed_before) return false;
  }
  return true;
}

bool MeshState::collapse_keeps_faces_apart(TriMesh::HalfedgeHandle h) const {
  const auto v0 = mesh_.from_vertex_handle(h);
  std::vector<Corners> old_faces;
  for (auto f : mesh_.vf_range(v0)) old_faces.push_back(corners(f));
  return faces_apart(faces_after_collapse(h), old_faces, [&](TriMesh::FaceHandle f) {
    for (auto v : mesh_.fv_range(f))
      if (v == v0) return true;
    return false;
  });
}

// Faces (a, b, c) and (b, a, d) become (c, a, d) and (d, b, c).
std::vector<MeshState::NewFace> MeshState::faces_after_flip(TriMesh::EdgeHandle e) const {
  const auto h0 = mesh_.halfedge_handle(e, 0);
  const auto h1 = mesh_.halfedge_handle(e, 1);
  const auto a = mesh_.from_vertex_handle(h0);
  const auto b = mesh_.to_vertex_handle(h0);
  const auto c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h0));
  const auto d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h1));
  const Vec3d n0 = normal_of(corners(mesh_.face_handle(h0)));
  const Vec3d n1 = normal_of(corners(mesh_.face_handle(h1)));
  auto make = [&](TriMesh::VertexHandle x, TriMesh::VertexHandle y, TriMesh::VertexHandle z, const Vec3d& n) {
    return NewFace{{point(x), point(y), point(z)}, n};
  };
  // Each new face is checked against both old normals.
  return {make(c, a, d, n0), make(d, b, c, n1), make(c, a, d, n1), make(d, b, c, n0)};
}

bool MeshState::flip_improves_locally(TriMesh::EdgeHandle e) const {
  if (mesh_.status(e).deleted() || mesh_.is_boundary(e)) return false;
  const auto h0 = mesh_.halfedge_handle(e, 0);
  if (locked_[mesh_.from_vertex_handle(h0).idx()] && locked_[mesh_.to_vertex_handle(h0).idx()]) return false;
  if (!(copies_[mesh_.face_handle(h0).idx()] == copies_[mesh_.opposite_face_handle(h0).idx()])) return false;
  const std::vector<NewFace> after = faces_after_flip(e);
  const double before_angle = std::min(smallest_angle(corners(mesh_.face_handle(h0))),
                                       smallest_angle(corners(mesh_.opposite_face_handle(h0))));
  const double after_angle = std::min(smallest_angle(after[0].corners), smallest_angle(after[1].corners));
  constexpr double kMinGain = 1e-3;  // radians; keeps flips from cycling on rounding noise
  if (!(after_angle > before_angle + kMinGain)) return false;
  if (!mesh_.is_flip_ok(e)) return false;
  if (!shapes_acceptable(after)) return false;
  // Both old and both new faces in one plane, none folded: the quad is convex
  // and both pairs tile it.
  const std::vector<Corners> old_faces{corners(mesh_.face_handle(h0)),
                                       corners(mesh_.opposite_face_handle(h0))};
  if (new_faces_within_old(old_faces, {after[0].corners, after[1].corners})) return true;
  return inside_envelope({after[0], after[1]}) && flip_keeps_carried_points(e, after);
}

bool MeshState::flip_keeps_faces_apart(TriMesh::EdgeHandle e) const {
  const auto f0 = mesh_.face_handle(mesh_.halfedge_handle(e, 0));
  const auto f1 = mesh_.face_handle(mesh_.halfedge_handle(e, 1));
  std::vector<NewFace> after = faces_after_flip(e);
  after.resize(2);
  return faces_apart(after, {corners(f0), corners(f1)},
                     [&](TriMesh::FaceHandle f) { return f == f0 || f == f1; });
}

}  // namespace mr::simplify
