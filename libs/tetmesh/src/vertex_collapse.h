#pragma once
// Removing a vertex by collapsing it onto a neighbour: the star of v is
// re-filled by the cone from neighbour u over the star's boundary. Used to
// get rid of cut points that cannot be rounded to doubles, typically points
// closer than a rounding step to another vertex (a plane passing within
// 1e-16 of a vertex without containing it).

#include "convex_cells.h"

#include <mr/tetmesh/mesh.h>

#include <array>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

namespace mr::tetmesh::detail {

/// The star's boundary as the cone from a new apex needs it: faces of the
/// star's tets not shared with another star tet (with their marks), the
/// tets beyond them, and the hull faces through removed vertices. The same
/// for every apex tried: compute it once per star.
struct StarBoundary {
  std::deque<std::vector<std::uint32_t>> storage;  ///< marks the faces point to (stable addresses)
  std::vector<CellTriangle> faces;
  std::vector<Index> outside;
  std::vector<std::array<Index, 3>> hull_faces;
};

/// `star` lists the live tets having a vertex of `removed` as a corner, each once.
StarBoundary star_boundary(const Mesh& mesh, std::span<const Index> removed, std::span<const Index> star);

/// Collapses the vertices `removed` onto u (not among them) if every new tet
/// is strictly positive (exact) and none of them is on the hull. `boundary`
/// is star_boundary(mesh, removed, star) of the mesh as it is. Marked faces
/// through removed vertices move to u (faces that shrink to an edge
/// vanish); marks on the star's boundary stay. Returns false, changing
/// nothing, when the collapse is not valid. `created`, if given, receives
/// the new tets.
bool collapse_vertices(Mesh& mesh, std::span<const Index> removed, Index u, std::span<const Index> star,
                       const StarBoundary& boundary, std::vector<Index>* created = nullptr);

}  // namespace mr::tetmesh::detail
