#pragma once
// The surface as patches are accepted into it, and the exact test that
// decides whether a patch may be: it must add no degenerate face, no
// vertex where one already is, no edge of more than two faces, and meet
// the surface and itself only in the vertices and edges they share.

#include <mr/core/triangle_soup.h>
#include <mr/spatial/box_grid.h>

#include <cstdint>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace mr::hole_fill::detail {

/// Positions and faces of a patch over the surface's vertices: face
/// indices below the surface's vertex count name its vertices, the others
/// name new_positions (numbered from the surface's vertex count on).
struct GlobalPatch {
  std::vector<Vec3d> new_positions;
  std::vector<Triangle> faces;
};

class FilledSurface {
 public:
  /// `welded`: welded by index (no two vertices share a position).
  explicit FilledSurface(TriangleSoup welded);

  const TriangleSoup& surface() const { return soup_; }
  /// The surface, moved out (the object is done with).
  TriangleSoup release() && { return std::move(soup_); }
  std::size_t num_vertices() const { return soup_.positions.size(); }

  /// Why `patch` may not be added ("a face crosses the surface", ...), or
  /// an empty string when it may. Decided with exact predicates.
  std::string refusal(const GlobalPatch& patch) const;
  void add(const GlobalPatch& patch);
  /// Whether two faces of the surface meet except in the vertices and
  /// edges they share (degenerate faces skipped). Parallel (TBB).
  bool meets_itself() const;

 private:
  struct PositionHash {
    std::size_t operator()(const Vec3d& p) const;
  };

  const Vec3d& position(Index v, const GlobalPatch& patch) const;
  std::string vertex_refusal(const GlobalPatch& patch) const;
  std::string edge_refusal(const GlobalPatch& patch) const;
  std::string intersection_refusal(const GlobalPatch& patch) const;
  void insert_face(std::uint32_t face);

  TriangleSoup soup_;
  spatial::BoxGrid boxes_;
  double cell_size_ = 1.0;
  std::unordered_map<std::uint64_t, int> edge_faces_;  ///< faces per undirected edge
  std::unordered_set<Vec3d, PositionHash> positions_;
};

}  // namespace mr::hole_fill::detail
