#pragma once
// Independent verification of a surface: topology counts, exact degeneracy,
// exact self-intersections and enclosed volume. Used by tests, by the
// mesh-check tool and by the benchmark runner; never by the algorithms it checks.

#include <mr/core/triangle_soup.h>

#include <cstdint>
#include <string>

namespace mr::check {

struct SurfaceReport {
  std::size_t vertices = 0;  ///< after welding bit-identical positions
  std::size_t faces = 0;
  std::size_t boundary_edges = 0;             ///< edges with one face
  std::size_t nonmanifold_edges = 0;          ///< edges with more than two faces
  std::size_t nonmanifold_vertices = 0;       ///< vertices whose faces form more than one fan
  std::size_t inconsistent_edges = 0;         ///< two-face edges traversed the same way by both
  std::size_t degenerate_faces = 0;           ///< exactly collinear corners or repeated vertex
  std::size_t duplicate_faces = 0;            ///< same vertex set as an earlier face
  std::size_t components = 0;                 ///< connected through shared vertices
  std::int64_t self_intersecting_pairs = -1;  ///< exact; -1 when not computed
  double volume = 0;                          ///< signed enclosed volume (meaningful when closed)

  bool closed() const { return boundary_edges == 0; }
  bool manifold() const { return nonmanifold_edges == 0 && nonmanifold_vertices == 0; }
  /// Closed, manifold, consistently oriented, outward, no degenerate face and
  /// no self-intersection (which must have been computed).
  bool watertight() const {
    return closed() && manifold() && inconsistent_edges == 0 && degenerate_faces == 0 &&
           self_intersecting_pairs == 0 && volume > 0;
  }
};

struct SurfaceCheckOptions {
  bool self_intersections = true;  ///< the costly part: exact pairwise tests after a box broad phase
};

SurfaceReport check_surface(const TriangleSoup& soup, const SurfaceCheckOptions& options = {});

/// What keeps a report from being watertight, e.g. "3 self-intersecting face
/// pairs, 1 non-manifold vertex"; empty when it is watertight.
std::string watertight_failures(const SurfaceReport& report);

}  // namespace mr::check
