#pragma once
// Stage 4 of the pipeline: insert every input triangle into the background
// mesh so that it becomes a union of mesh faces, marked with the triangle's
// id (the tracked surface). Exact: triangles that cross, overlap coplanar,
// touch or repeat are all handled by exact predicates on hybrid positions
// (rational cut points, rounded to doubles wherever no tet inverts).

#include <mr/core/errors.h>
#include <mr/core/triangle_soup.h>
#include <mr/tetmesh/logger.h>
#include <mr/tetmesh/mesh.h>

#include <cstdint>
#include <span>
#include <vector>

namespace mr::tetmesh {

struct InsertionStats {
  std::size_t inserted = 0;    ///< triangles and polygons cut into the mesh
  std::size_t polygons = 0;    ///< of those, convex polygons of several coplanar triangles
  std::size_t merged = 0;      ///< triangles embedded as part of an earlier one's polygon
  std::size_t degenerate = 0;  ///< skipped: collinear corners, nothing to embed
  std::size_t copies = 0;      ///< repeats of an earlier triangle's corners: marked, not cut again
  std::size_t cut_tets = 0;
  std::size_t rebuilt_tets = 0;
  std::size_t new_tets = 0;
  std::size_t new_vertices = 0;
  std::size_t steiner_points = 0;
  std::size_t eagerly_rounded = 0;  ///< cut points too long to keep exact, rounded at once
  std::size_t already_faces = 0;    ///< of `inserted`, triangles that were mesh faces: marked, not cut
  std::size_t snapped_points = 0;   ///< cut points moved onto a later plane (InsertionOptions::snap_distance)
  std::size_t settled_points = 0;   ///< cut points collapsed away inside the polygon that made them
  std::size_t skipped = 0;          ///< left out on request (see `skip`)
  std::size_t rational_vertices = 0;  ///< still rational when insertion ended
  /// Per vertex slot, the id of the triangle whose insertion created the
  /// vertex; kNoCreator for the vertices of the background mesh.
  std::vector<std::uint32_t> vertex_creator;
  /// Per input triangle, the id its faces are marked with: its own, or that
  /// of the first triangle of the coplanar polygon it was inserted in.
  std::vector<std::uint32_t> marked_as;
  static constexpr std::uint32_t kNoCreator = 0xffffffffu;
};

struct InsertionOptions {
  /// A cut point whose exact coordinates grow past this many bits (cuts of
  /// cuts multiply the length) is rounded as soon as its triangle is in, if
  /// no tet around it inverts; the others wait for the rounding stage.
  std::size_t max_exact_bits = 16384;
  /// A cut point on no tracked face (nor the hull) closer than this to the
  /// plane of a later polygon is moved onto it, exactly, when no tet around
  /// it inverts: the plane then passes through it instead of cutting its
  /// edges beside it (0: never). The tracked faces do not move.
  double snap_distance = 0.0;
  /// Once a polygon is in, collapse away the cut points it made inside its
  /// own faces or off every tracked face, where every tet around stays
  /// positive (triangle_inserter_settle.cpp): the tracked surface covers
  /// the same regions, and later planes have fewer thin tets to cut. Pair
  /// it with random_order: in a CAD model's input order, settled coplanar
  /// patches were cut along each other's lines until their exact points
  /// were 100,000 bits long.
  bool settle_cut_points = true;
  /// Insert the triangles in a seeded random order (the same on every
  /// machine) instead of the input's: fewer cut points where neighbours'
  /// planes cut each other's thin tets (insertion.cpp).
  bool random_order = false;
  /// Insert edge-adjacent triangles that lie in one plane with the same
  /// orientation as one convex polygon (coplanar_polygons.h): the edges
  /// between them are not cut into the mesh, and the polygon's faces carry
  /// the id of its first triangle only (see InsertionStats::marked_as).
  bool merge_coplanar = true;
  /// When the mesh grows past this many tets, insertion stops with
  /// InsertionTooCostly (0: no limit): a caller with a cheaper way (an
  /// input simplified first) takes it instead of waiting.
  std::size_t max_tets = 0;
};

/// Insertion passed InsertionOptions::max_tets.
class InsertionTooCostly : public RunError {
 public:
  using RunError::RunError;
};

/// Insertion passed TetrahedralizeOptions::max_rebuild_insertion_tets:
/// rebuilding every face costs too much as well.
class RebuildTooCostly : public InsertionTooCostly {
 public:
  using InsertionTooCostly::InsertionTooCostly;
};

/// Inserts the triangles of `input` in order; the faces of triangle i are
/// marked with id i, or with marked_as[i] when it was merged into a polygon.
/// `input_vertex` maps input vertices to mesh vertices (BackgroundMesh).
/// Triangles with skip[i] != 0 are left out (`skip` empty: none). Cut
/// points are left rational: rounding_stage rounds them afterwards.
/// Throws mr::RunError if an internal consistency check fails.
InsertionStats insert_triangles(Mesh& mesh, const TriangleSoup& input, std::span<const Index> input_vertex,
                                std::span<const char> skip = {}, const Logger& logger = {},
                                const InsertionOptions& options = {});

}  // namespace mr::tetmesh
