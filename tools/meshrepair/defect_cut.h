#pragma once
// Repair by cutting defects out: where a surface's defects are few and
// local (a fold, a few crossing or repeated faces, a non-manifold edge),
// the faces that are defects, and a band of vertex rings around them, are
// taken out and the holes left are filled. Every other input face is kept
// as it is, at any size, with no tets; the result is accepted only when it
// is watertight (exact) and stays within epsilon of the input both ways.
// Parts that cross each other are not cut: they need their union.

#include <mr/core/coordinate_grid.h>
#include <mr/core/triangle_soup.h>
#include <mr/hole_fill/hole_fill.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace mr::tools {

struct DefectCutOptions {
  /// Bands tried around the defect faces, in vertex rings, narrowest first.
  std::vector<int> rings{0, 1, 2};
  /// Defects are local when the defect faces are at most this share of the
  /// faces; otherwise (parts crossing each other all along, a soup) the cut
  /// is not tried.
  double max_defect_share = 0.1;
  /// Wider bands are not tried once a band cuts more than this share of the
  /// faces, or than min_cut_faces where that is more: each try fills and
  /// checks every hole again, which on a large input costs more than the
  /// tets.
  double max_cut_share = 0.1;
  std::size_t min_cut_faces = 5000;
  /// How far the filled surface and the input may be from each other
  /// (sampled both ways).
  double epsilon = 0.0;
  /// The grid the output is written on: new vertices are checked on it.
  CoordinateGrid grid = CoordinateGrid::doubles();
};

struct DefectCut {
  std::optional<hole_fill::HoleFillResult> fill;  ///< set when accepted: watertight, not yet oriented
  std::string declined;                           ///< why not, when fill is unset
  int rings = -1;                                 ///< the band accepted
  std::size_t faces = 0;                          ///< faces looked at (0: the cut was not needed)
  std::size_t defect_faces = 0;                   ///< faces that are defects
  /// The defect faces are at most DefectCutOptions::max_defect_share of the
  /// faces (or the only defects are holes, and no cut was needed).
  bool local = true;
  std::size_t cut_faces = 0;  ///< faces taken out (defects and band)
  double volume = 0.0;        ///< the accepted surface's signed volume
};

/// Cuts the defects out of `welded` (welded by identical positions, faces
/// turned to agree with their neighbours, no zero-area face) and fills the
/// holes, trying each band of options.rings until one is accepted.
DefectCut cut_out_defects(const TriangleSoup& welded, const DefectCutOptions& options);

}  // namespace mr::tools
