#pragma once
// Helpers on a plain list of tets: outward faces, vertex stars, which tets
// share a face, classes of tets connected through shared faces, and which
// tets make up the solid the manifold fix works on.

#include <mr/core/tet_mesh.h>

#include <cstdint>
#include <span>
#include <vector>

namespace mr::repair::detail {

inline constexpr Index kNoTet = Index(-1);

/// Face k of a positively oriented tet, oriented outward; the same
/// convention as mr::extract_boundary.
inline constexpr int kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

Triangle tet_face(const Tet& tet, int k);
bool has_corner(const Tet& tet, Index v);
double tet_volume(const std::vector<Vec3d>& positions, const Tet& tet);

/// For every vertex, the tets using it, in increasing order.
class VertexStars {
 public:
  VertexStars(const std::vector<Tet>& tets, std::size_t vertices);
  /// Only the stars of `wanted` (any other vertex's is empty): a round of
  /// the manifold fix asks those of a few dozen defect vertices of millions.
  VertexStars(const std::vector<Tet>& tets, std::size_t vertices, std::span<const Index> wanted);
  std::span<const Index> of(Index v) const {
    return {tets_.data() + offsets_[v], tets_.data() + offsets_[v + 1]};
  }

 private:
  /// The stars of the vertices flagged in `asked`.
  VertexStars(const std::vector<Tet>& tets, std::size_t vertices, const std::vector<char>& asked);

  std::vector<std::size_t> offsets_;
  std::vector<Index> tets_;
};

/// For every face of every tet, the other tet with the same three corners.
/// Depends only on which tets share faces, so renaming a vertex in the tets
/// of one face-connected class around it (a split) leaves it valid.
class FaceNeighbours {
 public:
  /// Throws mr::RunError when three tets share a face (not an embedding).
  explicit FaceNeighbours(const std::vector<Tet>& tets);
  Index across(Index tet, int face) const { return across_[4 * std::size_t(tet) + face]; }

 private:
  std::vector<Index> across_;
};

/// What a tet is to the solid, and what the manifold fix may still do with
/// it. States only move forward (rejected -> solid -> locked_out): no tet is
/// added twice, so the fix cannot go round in circles.
enum class TetState : std::uint8_t {
  solid,       ///< in the solid (kept by the filter or added by the fix); may be removed
  rejected,    ///< outside the solid; may be added
  locked_out,  ///< outside and stays there (removed, or next to a split vertex)
};

inline bool in_solid(TetState s) { return s == TetState::solid; }

/// Face `face` of tet `tet`.
struct FaceRef {
  Index tet;
  int face;
};

/// The faces of the solid's tets that no other tet of the solid shares, in
/// tet order.
std::vector<FaceRef> boundary_faces(const FaceNeighbours& neighbours, std::span<const TetState> states);

/// Face k of solid tet t is on the boundary of the solid.
inline bool on_boundary(const FaceNeighbours& neighbours, std::span<const TetState> states, Index t, int k) {
  const Index other = neighbours.across(t, k);
  return other == kNoTet || !in_solid(states[other]);
}

/// `subset` split into classes of tets connected through faces they share;
/// classes ordered by decreasing size, then by smallest tet.
std::vector<std::vector<Index>> face_connected_classes(const FaceNeighbours& neighbours,
                                                       std::span<const Index> subset);

}  // namespace mr::repair::detail
