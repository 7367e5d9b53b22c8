#include "vertex_collapse.h"

#include "convex_cells.h"

#include <algorithm>
#include <deque>
#include <vector>

namespace mr::tetmesh::detail {
namespace {

using Ids = std::vector<std::uint32_t>;

struct MovedMark {
  std::array<Index, 3> face;  // with u in place of v
  Ids ids;
};

std::array<Index, 3> sorted3(std::array<Index, 3> f) {
  std::sort(f.begin(), f.end());
  return f;
}

bool contains(std::span<const Index> set, Index v) {
  return std::find(set.begin(), set.end(), v) != set.end();
}

// Tracked faces through removed vertices that survive the collapse as faces
// through u (a face keeping three distinct corners).
std::vector<MovedMark> marks_through(const Mesh& mesh, std::span<const Index> removed, Index u,
                                     std::span<const Index> star) {
  std::vector<MovedMark> moved;
  for (Index t : star) {
    for (int k = 0; k < 4; ++k) {
      if (!mesh.is_surface_face(t, k)) continue;
      std::array<Index, 3> f = mesh.face_vertices(t, k);
      bool through = false;
      for (Index& corner : f) {
        if (contains(removed, corner)) {
          corner = u;
          through = true;
        }
      }
      if (!through || f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) continue;
      const auto ids = mesh.surface_ids(t, k);
      moved.push_back({sorted3(f), Ids(ids.begin(), ids.end())});
    }
  }
  return moved;
}

void apply_moved_marks(Mesh& mesh, std::span<const Index> created, const std::vector<MovedMark>& moved) {
  for (const MovedMark& mark : moved) {
    for (Index t : created) {
      const int k = [&] {
        for (int j = 0; j < 4; ++j) {
          if (sorted3(mesh.face_vertices(t, j)) == mark.face) return j;
        }
        return -1;
      }();
      if (k < 0) continue;
      const auto old = mesh.surface_ids(t, k);
      Ids ids(old.begin(), old.end());
      ids.insert(ids.end(), mark.ids.begin(), mark.ids.end());
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      mesh.set_surface_ids(t, k, ids);
      break;
    }
  }
}

}  // namespace

StarBoundary star_boundary(const Mesh& mesh, std::span<const Index> removed, std::span<const Index> star) {
  // Membership in the star by binary search: the star of a cut point where
  // many sheets cross has thousands of tets, and a linear search per face
  // made each collapse tried there quadratic.
  std::vector<Index> sorted;
  if (!std::is_sorted(star.begin(), star.end())) {
    sorted.assign(star.begin(), star.end());
    std::sort(sorted.begin(), sorted.end());
  }
  const std::span<const Index> in_star = sorted.empty() ? star : std::span<const Index>(sorted);
  StarBoundary boundary;
  for (Index t : star) {
    for (int k = 0; k < 4; ++k) {
      const Index n = mesh.neighbour(t, k);
      if (n != kNoTet && std::binary_search(in_star.begin(), in_star.end(), n)) continue;  // inside the star
      const std::array<Index, 3> f = mesh.face_vertices(t, k);
      if (n == kNoTet && (contains(removed, f[0]) || contains(removed, f[1]) || contains(removed, f[2]))) {
        boundary.hull_faces.push_back(f);
        continue;
      }
      const auto ids = mesh.surface_ids(t, k);
      const Ids* stored = ids.empty() ? nullptr : &boundary.storage.emplace_back(ids.begin(), ids.end());
      boundary.faces.push_back({f, stored});
      if (n != kNoTet) boundary.outside.push_back(n);
    }
  }
  return boundary;
}

bool collapse_vertices(Mesh& mesh, std::span<const Index> removed, Index u, std::span<const Index> star,
                       const StarBoundary& boundary, std::vector<Index>* created_tets) {
  // A hull face through a removed vertex vanishes; the cone's side faces
  // replace it, on the same plane only if u is on that plane.
  for (const std::array<Index, 3>& f : boundary.hull_faces)
    if (orient3d(mesh.position(u), mesh.position(f[0]), mesh.position(f[1]), mesh.position(f[2])) != 0)
      return false;
  if (!sees_all(mesh, mesh.position(u), u, boundary.faces)) return false;

  const std::vector<MovedMark> moved = marks_through(mesh, removed, u, star);
  std::vector<ConeTet> tets;
  cone(u, boundary.faces, tets);
  for (Index t : star) mesh.remove_tet(t);
  std::vector<Index> created;
  for (const ConeTet& tet : tets) {
    const Index t = mesh.add_tet(tet.corners);
    for (int k = 0; k < 4; ++k) {
      if (tet.face_ids[k] != nullptr) mesh.set_surface_ids(t, k, *tet.face_ids[k]);
    }
    created.push_back(t);
  }
  for (Index v : removed) mesh.remove_vertex(v);
  std::vector<Index> to_connect = created;
  to_connect.insert(to_connect.end(), boundary.outside.begin(), boundary.outside.end());
  mesh.connect(to_connect);
  apply_moved_marks(mesh, created, moved);
  if (created_tets != nullptr) *created_tets = std::move(created);
  return true;
}

}  // namespace mr::tetmesh::detail
