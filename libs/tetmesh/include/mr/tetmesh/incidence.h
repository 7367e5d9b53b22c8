#pragma once
// Vertex-to-tet incidence, computed on demand: the Mesh stores none, so
// operations never have to keep it up to date.

#include <mr/tetmesh/mesh.h>

#include <span>
#include <vector>

namespace mr::tetmesh {

/// For every vertex slot, the live tets using it (increasing tet index),
/// in compressed rows.
class VertexTets {
 public:
  explicit VertexTets(const Mesh& mesh);
  std::span<const Index> of(Index v) const {
    return {tets_.data() + offsets_[v], tets_.data() + offsets_[v + 1]};
  }

 private:
  std::vector<std::size_t> offsets_;
  std::vector<Index> tets_;
};

/// The live tets around vertex v, found by walking the adjacency from
/// `seed`, a live tet that has v as a corner (mr::UsageError otherwise).
/// Sorted by tet index. Cost: proportional to the size of the star.
std::vector<Index> tets_around_vertex(const Mesh& mesh, Index v, Index seed);

/// The live tets around edge (a, b), found by walking the faces that contain
/// it from `seed`, a live tet with both as corners (mr::UsageError
/// otherwise). Sorted by tet index. Cost: proportional to the edge's valence.
std::vector<Index> tets_around_edge(const Mesh& mesh, Index a, Index b, Index seed);

/// A live tet with corners a and b, found by walking a's star from `seed` (a
/// live tet with corner a, mr::UsageError otherwise) until one has b; kNoTet
/// if none has. Cost: at most the size of a's star, usually far less.
Index tet_with_edge(const Mesh& mesh, Index a, Index b, Index seed);

}  // namespace mr::tetmesh
