#pragma once
// Removing a vertex by collapsing it onto a neighbour: the star of v is
// re-filled by the cone from neighbour u over the star's boundary. Used to
// get rid of cut points that cannot be rounded to doubles, typically points
// closer than a rounding step to another vertex (a plane passing within
// 1e-16 of a vertex without containing it).

#include <mr/tetmesh/mesh.h>

#include <span>

namespace mr::tetmesh::detail {

/// Collapses the vertices `removed` onto u (not among them) if every new tet
/// is strictly positive (exact) and none of them is on the hull. `star`
/// lists the live tets having a removed vertex as a corner, each once.
/// Marked faces through removed vertices move to u (faces that shrink to an
/// edge vanish); marks on the star's boundary stay. Returns false, changing
/// nothing, when the collapse is not valid.
bool collapse_vertices(Mesh& mesh, std::span<const Index> removed, Index u, std::span<const Index> star);

}  // namespace mr::tetmesh::detail
