#pragma once
// The options of the whole tetrahedralization pipeline (user inputs only,
// with the paper's and fTetWild's defaults) and the parameters derived from
// them and the input (absolute lengths), kept apart so that what a user set
// is never confused with what was computed.

#include <mr/core/triangle_soup.h>

namespace mr::tetmesh {

/// Which tets the final filter keeps (stage 6).
enum class WindingRule {
  positive,  ///< w > 1/2, as the paper: outward-oriented input
  absolute,  ///< |w| > 1/2: also keeps solids whose faces all point inward
};

struct TetrahedralizeOptions {
  /// Envelope radius relative to the input's bounding-box diagonal b; used
  /// when epsilon_abs is 0.
  double epsilon_rel = 1e-3;
  double epsilon_abs = 0.0;
  /// Target edge length relative to b; used when edge_length_abs is 0.
  double edge_length_rel = 1.0 / 20.0;
  double edge_length_abs = 0.0;
  /// Voxel-stuffing lattice spacing relative to b (paper: b/20), at least
  /// the target edge length; 0 disables the lattice (the background mesh
  /// then has the input and the box corners).
  double lattice_spacing_rel = 1.0 / 20.0;
  /// Lattice points within this distance (relative to b) of the input are
  /// dropped (paper: delta = b/40, and delta must exceed epsilon).
  double lattice_clearance_rel = 1.0 / 40.0;
  /// Mesh improvement stops when the largest AMIPS energy is below this.
  double stop_energy = 10.0;
  /// Upper bound on mesh-improvement passes.
  int max_passes = 80;
  /// |w| > 1/2 by default: a model whose faces all point inward (a common
  /// export defect) is still a solid, where w > 1/2 would keep nothing.
  WindingRule winding_rule = WindingRule::absolute;
  /// Grid the surface is snapped to before insertion, relative to epsilon
  /// (rounded down to a power of two; 0: coordinates as they are). Noise
  /// below it (float files, CAD exports) otherwise makes nearly coplanar
  /// faces cut each other into points closer than doubles can hold.
  double snap_fraction = 1e-3;
  /// Largest snap_fraction accepted: the grid must stay far inside epsilon.
  static constexpr double kMaxSnapFraction = 0.01;
  /// Skip the input simplification stage.
  bool skip_simplify = false;
  /// Simplify only the faces near defects (within defect_band_rings vertex
  /// rings of a degenerate face, a face meeting another improperly, an edge
  /// of other than two faces or of two disagreeing ones); the others are
  /// inserted as they are, so that meshrepair can keep them.
  bool simplify_near_defects_only = false;
  /// The band simplify_near_defects_only simplifies, in vertex rings around
  /// the defect faces (0: the defect faces only).
  int defect_band_rings = 2;
  /// Insertion stops with InsertionTooCostly past this many tets (0: never)
  /// where faces are kept unsimplified (simplify_near_defects_only, some
  /// face away from every defect): it bounds what keeping them costs. A
  /// rebuild of every face has max_rebuild_insertion_tets instead.
  std::size_t max_insertion_tets = 0;
  /// The bound of an insertion that rebuilds every face (none kept, or a
  /// band around defects that holds every face), in tets (0: never).
  /// Passing it throws RebuildTooCostly: meshrepair then takes the outer
  /// hull instead (docs/ARCHITECTURE.md, "Repair").
  std::size_t max_rebuild_insertion_tets = 0;
  /// Worker threads; 0 means all hardware threads.
  int threads = 0;
};

/// Absolute values for one input. Invariant: all lengths are positive and
/// finite, lattice_clearance > epsilon when lattice_spacing > 0.
struct DerivedParameters {
  Vec3d input_min = Vec3d::Zero();  ///< bounding box of the input vertices
  Vec3d input_max = Vec3d::Zero();
  double diagonal = 0.0;  ///< b
  double epsilon = 0.0;
  double edge_length = 0.0;        ///< ell
  double lattice_spacing = 0.0;    ///< 0: no lattice
  double lattice_clearance = 0.0;  ///< delta
  double snap_spacing = 0.0;       ///< a power of two; 0: no snapping
  /// Margin between the input's box and the background box: max(ell, 2 epsilon),
  /// as fTetWild (see derive_parameters).
  double box_margin = 0.0;
  Vec3d box_min = Vec3d::Zero();  ///< background box
  Vec3d box_max = Vec3d::Zero();
};

/// Computes the derived parameters. Throws mr::UsageError on a non-finite or
/// negative option, on epsilon or edge length that end up non-positive, or
/// on a lattice clearance not larger than epsilon; throws mr::RunError when
/// the input has no vertex or a zero bounding-box diagonal (nothing to mesh).
DerivedParameters derive_parameters(const TetrahedralizeOptions& options, const TriangleSoup& input);

}  // namespace mr::tetmesh
