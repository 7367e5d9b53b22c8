#pragma once
// The winding number of an open surface at every tet's centroid, without
// asking the surface for every tet.
//
// The surface S is open: its boundary is a set of closed loops. Capping
// each loop with triangles between its own vertices (a surface D with the
// same boundary, mostly small triangles along the loop) gives a cycle S - D,
// whose winding number is an integer that changes by exactly +1 or -1
// where a path passes through one of its triangles. So
//
//   w_S(c) = w_{S-D}(c) + w_D(c),
//
// with w_D asked of the cap's triangles, and w_{S-D} carried from tet to
// tet along a spanning forest of the mesh: the signed count of triangles
// of S - D that the segment between two neighbours' centroids passes
// through, decided with exact orientation tests. S is made of faces of the
// mesh, which no tet's interior meets: when both centroids lie inside
// their tets and the segment passes through the interior of the face
// between them, that face is the only part of S it can cross, so only the
// cap's triangles are searched. A segment that touches a triangle anywhere
// but in a proper crossing of its interior carries nothing; its far end,
// like the first tet of every component, asks S itself and rounds w_S - w_D to the integer it must be.

#include <mr/core/triangle_soup.h>
#include <mr/tetmesh/mesh.h>
#include <mr/winding_number/winding_number.h>

#include <span>
#include <vector>

namespace mr::tetmesh {

/// A face of the mesh: face `face` of tet `tet` (opposite its corner `face`).
struct FaceRef {
  Index tet;
  int face;
};

struct OpenWindingStats {
  std::size_t cap_triangles = 0;
  /// Tets whose number was asked of the surface: one per component, plus
  /// those no crossing count could reach.
  std::size_t direct_queries = 0;
  /// Neighbours whose segment was tested against the whole surface, not
  /// only against the face between them.
  std::size_t full_crossing_tests = 0;
};

/// Per tet slot, the winding number of `surface` (a chain: triangles
/// repeated by multiplicity, vertices shared by index) at the centroid of
/// each live tet (0 for removed slots). Triangle i of `surface` is the mesh
/// face origins[i], with the same corners.
std::vector<double> open_surface_winding(const Mesh& mesh, const TriangleSoup& surface,
                                         std::span<const FaceRef> origins, OpenWindingStats& stats);

}  // namespace mr::tetmesh
