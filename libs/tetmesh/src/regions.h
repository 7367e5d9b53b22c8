#pragma once
// Helpers of the pipeline's last stages: region labels for unfiltered
// output, the tracked surface as a soup, and the final exact check.

#include <mr/core/tet_mesh.h>
#include <mr/core/triangle_soup.h>
#include <mr/tetmesh/mesh.h>
#include <mr/tetmesh/open_surface_winding.h>
#include <mr/tetmesh/winding_filter.h>

#include <array>
#include <span>
#include <vector>

namespace mr::tetmesh::detail {

/// Per tet slot, a label numbering the sets of tets connected through faces
/// that are not tracked surface: 1, 2, ... in order of their smallest tet
/// slot; 0 for removed slots. A tet with barrier[t] != 0 is a set of its own.
std::vector<std::int32_t> region_labels(const Mesh& mesh, std::span<const char> barrier = {});

/// Unit normal of triangle `id` of `input` (zero when it is degenerate).
Vec3d input_normal(const TriangleSoup& input, std::uint32_t id);

/// The tracked-surface faces of the tets with keep[t] != 0 (every live tet
/// when keep is empty), each once, oriented like the input triangle of its
/// smallest id, with its own vertices (doubles: call after rounding).
/// With Multiplicity::as_chain, each face counts once per input triangle on
/// it, +1 or -1 by orientation: faces where they cancel are left out and
/// the others repeated, so the soup is the integer chain the input makes
/// (a cycle for a closed input) and its winding number jumps correctly.
/// `origins`, when given, receives per triangle the face (tet, face) it is.
enum class Multiplicity { once, as_chain };
TriangleSoup tracked_surface(const Mesh& mesh, std::span<const char> keep, const TriangleSoup& input,
                             Multiplicity multiplicity = Multiplicity::once,
                             std::vector<FaceRef>* origins = nullptr);

/// Whether every edge of `surface` (vertices compared by index) is run along
/// as often one way as the other. The surface is then a closed cycle: its
/// winding number is an integer, constant on each region it bounds.
bool is_cycle(const TriangleSoup& surface);
/// The boundary of `surface` as a chain: each edge counted +1 one way and -1
/// the other, the ones left over directed by their sign and repeated by
/// their multiplicity, sorted. Empty for a cycle.
std::vector<std::array<Index, 2>> chain_boundary(const TriangleSoup& surface);
/// The edges (vertex pairs, lower index first) of `surface` not run along
/// as often one way as the other: chain_boundary's, each once.
std::vector<std::array<Index, 2>> unbalanced_edges(const TriangleSoup& surface);
/// How many edges of `surface` in `edges` have their midpoint farther than
/// `radius` from every triangle of `triangles` (all of them when there is none).
std::size_t edges_away_from(const TriangleSoup& surface, std::span<const std::array<Index, 2>> edges,
                            const TriangleSoup& triangles, double radius);

/// The number of tets of `mesh` that are not strictly positively oriented
/// on their double coordinates (exact orient3d; parallel).
std::size_t count_non_positive_tets(const TetMesh& mesh);

}  // namespace mr::tetmesh::detail
