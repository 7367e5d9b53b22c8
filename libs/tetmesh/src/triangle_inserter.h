#pragma once
// Stage 4 for one triangle, or one convex polygon of coplanar triangles
// (coplanar_polygons.h): cut the tets it crosses so that it becomes a union
// of mesh faces, exactly (docs/ARCHITECTURE.md, "Triangle insertion").
//
// For input polygon T (usually a triangle) with plane P:
// 1. candidates: the tets that may meet T (a conservative exact test),
//    found by walking from a tet at T's first corner; cut points closer to
//    P than the snap distance, on no tracked face, are first moved onto P
//    where no tet around them inverts (triangle_inserter_snap.cpp);
// 2. the candidates P crosses, where the section overlaps T, are cut by P: a rational point on each crossed
//    edge, the section polygon between the two halves;
// 3. every polygon on P (sections, and existing faces lying on P) is clipped
//    by the lines through T's edges; the pieces inside T are marked
//    with T's id;
// 4. the cavity (cut tets and every tet around an edge that got a new
//    point) is rebuilt from its convex cells (convex_cells.h), each polygon
//    triangulated canonically so that neighbours agree;
// Cut points stay rational here (rounding them at once made later planes
// pass within a rounding step of them, leaving knots of points that cannot be
// rounded); rounding_stage.h rounds them all once every triangle is in.
// Every decision is an exact predicate on the hybrid positions.

#include "convex_cells.h"

#include <mr/tetmesh/mesh.h>

#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace mr::tetmesh::detail {

struct InsertionCounters {
  std::size_t inserted = 0;
  std::size_t degenerate = 0;  ///< triangles with collinear corners: nothing to insert
  std::size_t cut_tets = 0;
  std::size_t rebuilt_tets = 0;  ///< tets of all cavities
  std::size_t new_tets = 0;
  std::size_t new_vertices = 0;     ///< cut points (Steiner points excluded)
  std::size_t steiner_points = 0;   ///< cell centres, where no corner could cone a cell
  std::size_t eagerly_rounded = 0;  ///< cut points rounded during insertion (too many bits)
  std::size_t already_faces = 0;    ///< triangles that were a mesh face already: marked, nothing cut
  std::size_t snapped_points = 0;   ///< cut points moved onto a later plane near them
  std::size_t settled_points = 0;   ///< cut points collapsed away inside the polygon they cut
};

class TriangleInserter {
 public:
  /// Cut points longer than `max_exact_bits` (bit_size) are rounded during
  /// insertion where nothing inverts; those closer than `snap_distance` to
  /// a later polygon's plane may be moved onto it (0: never); with `settle`,
  /// cut points inside the polygon that made them are collapsed away.
  TriangleInserter(Mesh& mesh, std::size_t max_exact_bits, double snap_distance = 0.0, bool settle = false);

  /// Most corners of a polygon insert() accepts.
  static constexpr std::size_t kMaxCorners = 12;

  /// Inserts the strictly convex polygon with these corners (mesh vertices,
  /// at most kMaxCorners, all in one plane; usually a triangle) and marks its
  /// faces with input id `id`. Returns false, changing nothing, when the
  /// first three corners are collinear.
  bool insert(std::span<const Index> corners, std::uint32_t id);

  const InsertionCounters& counters() const { return counters_; }
  /// Per vertex slot, the id of the triangle whose insertion created the
  /// vertex (kNoCreator for vertices of the background mesh).
  const std::vector<std::uint32_t>& creators() const { return creator_; }

  static constexpr std::uint32_t kNoCreator = std::numeric_limits<std::uint32_t>::max();

 private:
  using Ids = std::vector<std::uint32_t>;
  struct Piece {
    std::vector<Index> corners;
    Ids ids;
  };
  /// Sides of a vertex, computed once per polygon (2: not yet): valid
  /// while `stamp` is the current generation_.
  struct VertexSides {
    std::uint32_t stamp = 0;
    std::int8_t plane = 2;
    std::array<std::int8_t, kMaxCorners> lines{};
  };
  /// The pieces a face was split into, oriented like `oriented`.
  struct SplitFace {
    std::array<Index, 3> oriented;
    std::vector<Piece> pieces;
  };

  bool set_up_plane(std::span<const Index> corners, std::uint32_t id);
  bool mark_if_mesh_face();
  std::size_t line_count() const { return corners_.size(); }
  int plane_sign(Index v);
  int line_side(int line, Index v);
  VertexSides& sides_of(Index v);
  bool may_meet_polygon(Index t);
  void collect_candidates();
  void forget_candidates();
  std::size_t snap_points_near_plane();
  bool try_move_onto_plane(Index v);
  std::size_t settle_cut_points();
  std::vector<Index> settling_targets(Index v, std::span<const Index> star) const;
  bool collapse_cut_point(Index v);
  bool is_cut(Index t);
  bool section_outside_a_line(Index t);
  const HybridPoint& plane_point(Index u, Index v);
  bool overlaps_polygon(std::span<const HybridPoint> points);
  std::optional<bool> section_overlaps_filtered(const Tet& c);

  Index split_point(Index u, Index v, int line, Index seed_tet);
  void register_cut_points();
  std::vector<Index> section_polygon(Index t);
  std::pair<std::vector<Index>, std::vector<Index>> split_polygon(const std::vector<Index>& polygon, int line,
                                                                  Index seed_tet);
  std::vector<Piece> clip_by_polygon(std::vector<Index> polygon, const Ids& ids, Index seed_tet);
  void split_faces_of_cut_tets();
  void clip_faces_on_plane();
  void collect_cavity();
  Index next_around_edge(Index t, Index u, Index v, Index previous, bool first) const;
  void add_to_cavity(Index t);
  void walk_around_edge(Index u, Index v, Index seed);

  std::vector<Index> with_flat_points(const std::vector<Index>& polygon,
                                      std::vector<std::uint32_t>& sides) const;
  void append_edge_interior(Index u, Index v, std::vector<Index>& out) const;
  std::vector<Piece> face_pieces(Index t, int face);
  void add_polygon(const std::vector<Index>& polygon, const Ids& ids, int plane,
                   std::vector<CellTriangle>& cell);
  void build_cell(std::vector<CellTriangle>& cell, std::vector<ConeTet>& tets);
  void rebuild_cavity();
  void round_oversized_points(std::span<const Index> created);
  void note_new_vertex(Index v);

  bool stamped(std::vector<std::uint32_t>& stamps, Index t) const;
  void stamp(std::vector<std::uint32_t>& stamps, Index t);

  Mesh& mesh_;
  std::size_t max_exact_bits_;
  double snap_distance_;
  bool settle_;
  std::vector<Index> seed_tet_;  ///< per vertex slot, a live tet having it as a corner
  std::vector<std::uint32_t> creator_;
  InsertionCounters counters_;

  // ---- state of the current polygon ----
  std::uint32_t generation_ = 0;
  std::uint32_t id_ = 0;
  std::vector<Index> corners_;
  std::vector<HybridPoint> line_lift_;  ///< corner i + unit vector along axis_: the line planes
  int axis_ = 0;                        ///< projection axis for the lines through T's edges
  int orientation_ = 1;                 ///< sign making T's interior positive for line_side
  std::vector<VertexSides> sides_;  ///< per vertex slot: a lookup, not a hash (most of the candidate walk)
  std::vector<std::uint32_t> candidate_stamp_, cut_stamp_, cavity_stamp_;
  std::vector<Index> candidates_, cut_tets_, cavity_;
  std::unordered_map<std::uint64_t, HybridPoint> plane_points_;  ///< P on edge (sorted pair), computed once
  std::unordered_map<std::uint64_t, Index> splits_;              ///< segment (sorted pair) -> its new point
  std::vector<std::array<Index, 3>> split_mesh_edges_;           ///< u, v, a tet around the edge
  std::unordered_set<Index> new_vertices_;
  std::unordered_map<Index, std::vector<Piece>> section_pieces_;
  std::map<std::array<Index, 3>, SplitFace> split_faces_;  ///< key: sorted corners
  std::deque<Ids> ids_storage_;                            ///< ids that cell triangles point to
};

}  // namespace mr::tetmesh::detail
