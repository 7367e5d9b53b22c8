// Removed vertices carried by the faces nearest to them (see mesh_state.h):
// the bound from the input to the output.

#include "mesh_state.h"

#include <mr/spatial/triangle_distance.h>

#include <limits>

namespace mr::simplify {
namespace {

double squared_distance(const Vec3d& p, const Corners& c) {
  return spatial::closest_on_triangle(p, c[0], c[1], c[2]).squared_distance;
}

bool all_within(const std::vector<Vec3d>& points, const std::vector<Corners>& faces, double epsilon) {
  const double bound = epsilon * epsilon;
  for (const Vec3d& p : points) {
    bool near = false;
    for (const Corners& c : faces)
      if (squared_distance(p, c) <= bound) {
        near = true;
        break;
      }
    if (!near) return false;
  }
  return true;
}

std::vector<TriMesh::FaceHandle> faces_around(const TriMesh& mesh, TriMesh::VertexHandle v) {
  std::vector<TriMesh::FaceHandle> faces;
  for (auto f : mesh.vf_range(v)) faces.push_back(f);
  return faces;
}

}  // namespace

std::vector<Vec3d> MeshState::points_carried_by(const std::vector<TriMesh::FaceHandle>& faces) const {
  std::vector<Vec3d> points;
  for (auto f : faces)
    for (std::uint32_t i : carried_by_[f.idx()]) points.push_back(carried_positions_[i]);
  return points;
}

// The points on v0's faces, and v0 itself, must stay near the faces v1 has
// after the collapse: the rewritten fan and v1's faces the collapse leaves.
bool MeshState::collapse_keeps_carried_points(TriMesh::HalfedgeHandle h,
                                              const std::vector<NewFace>& faces) const {
  const auto v0 = mesh_.from_vertex_handle(h);
  std::vector<Vec3d> points = points_carried_by(faces_around(mesh_, v0));
  points.push_back(point(v0));
  std::vector<Corners> after;
  for (const NewFace& face : faces) after.push_back(face.corners);
  for (auto f : mesh_.vf_range(mesh_.to_vertex_handle(h))) {
    bool touches_v0 = false;
    for (auto v : mesh_.fv_range(f)) touches_v0 = touches_v0 || v == v0;
    if (!touches_v0) after.push_back(corners(f));
  }
  return all_within(points, after, tolerances_.epsilon);
}

// `faces` are faces_after_flip's: the first two are the new faces.
bool MeshState::flip_keeps_carried_points(TriMesh::EdgeHandle e, const std::vector<NewFace>& faces) const {
  const std::vector<Vec3d> points = points_carried_by(
      {mesh_.face_handle(mesh_.halfedge_handle(e, 0)), mesh_.face_handle(mesh_.halfedge_handle(e, 1))});
  return all_within(points, {faces[0].corners, faces[1].corners}, tolerances_.epsilon);
}

std::vector<std::uint32_t> MeshState::take_carried_points(const std::vector<TriMesh::FaceHandle>& faces) {
  std::vector<std::uint32_t> points;
  for (auto f : faces) {
    std::vector<std::uint32_t>& carried = carried_by_[f.idx()];
    points.insert(points.end(), carried.begin(), carried.end());
    carried.clear();
    carried.shrink_to_fit();
  }
  return points;
}

// Ties go to the first face in `faces`, so the result is deterministic.
void MeshState::carry_by_nearest(const std::vector<std::uint32_t>& points,
                                 const std::vector<TriMesh::FaceHandle>& faces) {
  std::vector<Corners> shapes;
  for (auto f : faces) shapes.push_back(corners(f));
  for (std::uint32_t i : points) {
    std::size_t nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < shapes.size(); ++k)
      if (const double d = squared_distance(carried_positions_[i], shapes[k]); d < best) {
        best = d;
        nearest = k;
      }
    carried_by_[faces[nearest].idx()].push_back(i);
  }
}

}  // namespace mr::simplify
