#pragma once
// Topological defects of a surface given by vertex indices (not positions):
// the repair's own bookkeeping, independent of mr::check.

#include <mr/core/types.h>

#include <array>
#include <span>
#include <vector>

namespace mr::repair::detail {

struct BoundaryDefects {
  std::size_t boundary_edges = 0;                       ///< edges with one face
  std::vector<std::array<Index, 2>> nonmanifold_edges;  ///< more than two faces; sorted (a < b)
  /// Vertices whose faces form more than one fan (connected through edges
  /// at the vertex), increasing.
  std::vector<Index> nonmanifold_vertices;

  bool manifold() const { return nonmanifold_edges.empty() && nonmanifold_vertices.empty(); }
  bool closed_manifold() const { return boundary_edges == 0 && manifold(); }
};

BoundaryDefects find_boundary_defects(std::span<const Triangle> triangles);

}  // namespace mr::repair::detail
