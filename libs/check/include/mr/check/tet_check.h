#pragma once
// Independent verification of a tet mesh: exact orientation of every tet on
// its double coordinates, element quality, and the boundary surface.

#include <mr/check/surface_check.h>
#include <mr/core/tet_mesh.h>

namespace mr::check {

struct TetReport {
  std::size_t vertices = 0;
  std::size_t tets = 0;
  std::size_t inverted_tets = 0;    ///< orient3d < 0, exact
  std::size_t degenerate_tets = 0;  ///< orient3d == 0, exact
  double volume = 0;
  double min_dihedral_deg = 0;      ///< over all tets
  double avg_min_dihedral_deg = 0;  ///< mean over tets of their smallest dihedral angle
  double max_amips = 0;             ///< conformal AMIPS energy; 3 for a regular tet
  double avg_amips = 0;
  SurfaceReport boundary;  ///< of all tets

  bool valid() const { return inverted_tets == 0 && degenerate_tets == 0 && tets > 0; }
};

TetReport check_tets(const TetMesh& mesh, const SurfaceCheckOptions& boundary_options = {});

/// Conformal AMIPS energy tr(J^T J) / det(J)^(2/3) of the map from a regular
/// tet; 3 for a regular tet, +infinity for one flat or inverted exactly
/// (near flat, det(J) is computed exactly).
double amips_energy(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);

/// The smallest of the six dihedral angles, in degrees.
double min_dihedral_angle_deg(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);

}  // namespace mr::check
