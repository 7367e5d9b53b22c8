#pragma once
// Stage 3 of the pipeline: the background tetrahedralization. A Delaunay
// tetrahedralization (CGAL) of the input vertices, the corners of the
// background box and the voxel-stuffing lattice of the paper's section 3.4.
// The input triangles are NOT embedded: stage 4 inserts them into this mesh.

#include <mr/core/triangle_soup.h>
#include <mr/spatial/aabb_tree.h>
#include <mr/tetmesh/mesh.h>
#include <mr/tetmesh/options.h>

#include <vector>

namespace mr::tetmesh {

struct BackgroundParameters {
  Vec3d box_min = Vec3d::Zero();  ///< the background box; must contain every input vertex strictly
  Vec3d box_max = Vec3d::Zero();
  double lattice_spacing = 0.0;    ///< 0: no lattice
  double lattice_clearance = 0.0;  ///< lattice points within this distance of the input are dropped
  int threads = 0;                 ///< 0: all hardware threads
  /// CGAL's parallel insertion (TBB, lock grid). Output is the same either
  /// way: the Delaunay tets of points in degenerate position are fixed by
  /// CGAL's symbolic perturbation, and the tets are sorted afterwards.
  /// Off by default: on the 2-core build machine it was 1.3-4x slower than
  /// sequential insertion (515k-face ogre: 1.3-1.4 s vs 3.7-5.8 s), the
  /// lock contention eating the second core. Try it on machines with more cores.
  bool parallel = false;
};

/// The parameters of DerivedParameters, in background-mesh terms.
BackgroundParameters background_parameters(const DerivedParameters& derived, int threads);

struct BackgroundMesh {
  /// Vertices: the distinct input positions (first occurrence order), then
  /// the 8 box corners (flag kOnBox), then the lattice points (kOnBox when on
  /// the box). Tets in a canonical order, positively oriented (checked exactly).
  Mesh mesh;
  /// For every input vertex, its mesh vertex (equal positions share one).
  std::vector<Index> input_vertex;
  std::size_t distinct_input_vertices = 0;
  std::size_t lattice_points = 0;
  double seconds_lattice = 0.0;
  double seconds_delaunay = 0.0;
  double seconds_mesh = 0.0;  ///< ordering, orientation check and adjacency
};

/// Builds the background mesh. `tree` is an AABB tree of `input` (used for
/// the lattice clearance). Throws mr::UsageError if the box does not strictly
/// contain the input or the lattice would exceed 10^8 points, mr::RunError if
/// the triangulation yields a tet that is not positively oriented (exact test).
BackgroundMesh build_background_mesh(const TriangleSoup& input, const spatial::AabbTree& tree,
                                     const BackgroundParameters& parameters);

/// The regular lattice over [box_min, box_max]: per axis n = max(1, round(extent /
/// spacing)) intervals, the last point exactly on box_max, x-major order.
/// Includes the box corners.
std::vector<Vec3d> lattice_points(const Vec3d& box_min, const Vec3d& box_max, double spacing);

/// The lattice points, box corners excluded, whose distance to the input
/// (tree) is larger than `clearance`, in lattice order. Parallel, deterministic.
std::vector<Vec3d> voxel_stuffing_points(const Vec3d& box_min, const Vec3d& box_max, double spacing,
                                         double clearance, const spatial::AabbTree& tree);

}  // namespace mr::tetmesh
