#include "regions.h"

#include <mr/core/orientation.h>

#include <mr/kernel/predicates.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <functional>

namespace mr::tetmesh::detail {

std::vector<std::int32_t> region_labels(const Mesh& mesh) {
  std::vector<std::int32_t> labels(mesh.tet_slots(), 0);
  std::int32_t next = 0;
  std::vector<Index> stack;
  for (Index seed = 0; seed < mesh.tet_slots(); ++seed) {
    if (!mesh.tet_alive(seed) || labels[seed] != 0) continue;
    labels[seed] = ++next;
    stack.push_back(seed);
    while (!stack.empty()) {
      const Index t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 4; ++k) {
        const Index n = mesh.neighbour(t, k);
        if (n == kNoTet || labels[n] != 0 || mesh.is_surface_face(t, k)) continue;
        labels[n] = next;
        stack.push_back(n);
      }
    }
  }
  return labels;
}

TriangleSoup tracked_surface(const Mesh& mesh, std::span<const char> keep, const TriangleSoup& input) {
  const auto kept = [&](Index t) { return t != kNoTet && mesh.tet_alive(t) && (keep.empty() || keep[t] != 0); };
  TriangleSoup surface;
  std::vector<double> votes;
  std::vector<Index> used(mesh.vertex_slots(), kNoVertex);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!kept(t)) continue;
    for (int k = 0; k < 4; ++k) {
      const Index n = mesh.neighbour(t, k);
      if (!mesh.is_surface_face(t, k) || (kept(n) && n < t)) continue;
      std::array<Index, 3> f = mesh.face_vertices(t, k);
      const Triangle& source = input.triangles[mesh.surface_ids(t, k).front()];
      const Vec3d input_normal = (input.positions[source[1]] - input.positions[source[0]])
                                     .cross(input.positions[source[2]] - input.positions[source[0]])
                                     .normalized();
      const Vec3d& a = mesh.position(f[0]).approx;
      double agreement = (mesh.position(f[1]).approx - a).cross(mesh.position(f[2]).approx - a).dot(input_normal);
      if (agreement < 0) {
        std::swap(f[1], f[2]);
        agreement = -agreement;
      }
      votes.push_back(agreement);
      Triangle out;
      for (int i = 0; i < 3; ++i) {
        if (used[f[i]] == kNoVertex) {
          used[f[i]] = static_cast<Index>(surface.positions.size());
          surface.positions.push_back(mesh.position(f[i]).approx);
        }
        out[i] = used[f[i]];
      }
      surface.triangles.push_back(out);
    }
  }
  // The normal test above is only a guess for faces that moved away from
  // the plane of their input triangle (improvement, or faces merged across a
  // crease): orient each patch coherently, trusting faces by how well
  // their normal agreed with their triangle's.
  orient_coherently(surface, votes);
  return surface;
}

std::size_t count_non_positive_tets(const TetMesh& mesh) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, mesh.tets.size()), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& range, std::size_t count) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const Tet& t = mesh.tets[i];
          count += orient3d(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]],
                            mesh.positions[t[3]]) <= 0;
        }
        return count;
      },
      std::plus<>());
}

}  // namespace mr::tetmesh::detail
