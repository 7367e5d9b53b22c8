#include <mr/tetmesh/incidence.h>

#include <mr/core/errors.h>

#include <algorithm>
#include <string>
#include <unordered_set>

namespace mr::tetmesh {

VertexTets::VertexTets(const Mesh& mesh) : offsets_(mesh.vertex_slots() + 1, 0) {
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (const Index v : mesh.tet(t)) ++offsets_[v + 1];
  }
  for (std::size_t v = 0; v + 1 < offsets_.size(); ++v) offsets_[v + 1] += offsets_[v];
  tets_.resize(offsets_.back());
  std::vector<std::size_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (const Index v : mesh.tet(t)) tets_[fill[v]++] = t;
  }
}

std::vector<Index> tets_around_vertex(const Mesh& mesh, Index v, Index seed) {
  if (!mesh.tet_alive(seed) || mesh.corner_of(seed, v) < 0) {
    throw UsageError("tets_around_vertex: seed tet " + std::to_string(seed) +
                     " is not a live tet with vertex " + std::to_string(v));
  }
  // A linear search of the star was quadratic: cut points on lines where
  // many triangles cross have thousands of tets around them.
  std::vector<Index> star{seed};
  std::unordered_set<Index> seen{seed};
  for (std::size_t i = 0; i < star.size(); ++i) {
    const Index t = star[i];
    const int opposite = mesh.corner_of(t, v);
    for (int f = 0; f < 4; ++f) {
      const Index u = mesh.neighbour(t, f);
      // Faces other than the one opposite v contain v: their neighbour is in the star.
      if (f == opposite || u == kNoTet) continue;
      if (seen.insert(u).second) star.push_back(u);
    }
  }
  std::sort(star.begin(), star.end());
  return star;
}

}  // namespace mr::tetmesh
