#include <mr/tetmesh/options.h>

#include <mr/core/errors.h>
#include <mr/core/grid_snap.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace mr::tetmesh {
namespace {

void require_non_negative(double value, const char* name) {
  if (!std::isfinite(value) || value < 0.0) {
    throw UsageError(std::string(name) + " must be a finite non-negative number, got " +
                     std::to_string(value));
  }
}

// An absolute value when given (> 0), else the relative one times b.
double absolute_or_relative(double absolute, double relative, double diagonal, const char* name) {
  const double value = absolute > 0.0 ? absolute : relative * diagonal;
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw UsageError(std::string(name) + " must be positive");
  }
  return value;
}

}  // namespace

DerivedParameters derive_parameters(const TetrahedralizeOptions& options, const TriangleSoup& input) {
  require_non_negative(options.epsilon_rel, "epsilon (relative)");
  require_non_negative(options.epsilon_abs, "epsilon (absolute)");
  require_non_negative(options.edge_length_rel, "edge length (relative)");
  require_non_negative(options.edge_length_abs, "edge length (absolute)");
  require_non_negative(options.lattice_spacing_rel, "lattice spacing (relative)");
  require_non_negative(options.lattice_clearance_rel, "lattice clearance (relative)");
  require_non_negative(options.snap_fraction, "snap fraction");
  // Simplification already uses 0.8 epsilon; snapping moves a vertex by up
  // to 0.87 of a grid step, and a retry may take a grid 16 times coarser.
  if (options.snap_fraction > TetrahedralizeOptions::kMaxSnapFraction) {
    throw UsageError("the snap fraction must be at most " +
                     std::to_string(TetrahedralizeOptions::kMaxSnapFraction) + " (of epsilon), got " +
                     std::to_string(options.snap_fraction));
  }
  require_non_negative(options.stop_energy, "stop energy");
  if (options.max_passes < 0) throw UsageError("max passes must not be negative");
  if (options.threads < 0) throw UsageError("threads must not be negative");
  if (input.positions.empty()) throw RunError("the input has no vertices: nothing to tetrahedralize");

  DerivedParameters p;
  p.input_min = p.input_max = input.positions.front();
  for (const Vec3d& v : input.positions) {
    p.input_min = p.input_min.cwiseMin(v);
    p.input_max = p.input_max.cwiseMax(v);
  }
  p.diagonal = (p.input_max - p.input_min).norm();
  if (!(p.diagonal > 0.0) || !std::isfinite(p.diagonal)) {
    throw RunError("the input's bounding box has no extent (or is not finite): nothing to tetrahedralize");
  }
  p.epsilon = absolute_or_relative(options.epsilon_abs, options.epsilon_rel, p.diagonal, "epsilon");
  p.edge_length =
      absolute_or_relative(options.edge_length_abs, options.edge_length_rel, p.diagonal, "edge length");
  // Never finer than the target: a finer lattice only adds points the
  // collapses must take away, and they cannot take all (a unit cube at
  // -l 0.1 kept 5,865 tets on the b/20 lattice, more than at -l 0.08).
  p.lattice_spacing = options.lattice_spacing_rel > 0.0
                          ? std::max(options.lattice_spacing_rel * p.diagonal, p.edge_length)
                          : 0.0;
  p.lattice_clearance = options.lattice_clearance_rel * p.diagonal;
  if (p.lattice_spacing > 0.0 && !(p.lattice_clearance > p.epsilon)) {
    throw UsageError(
        "the lattice clearance (delta) must exceed epsilon, or lattice points could "
        "sit inside the envelope");
  }
  const double snap = options.snap_fraction * p.epsilon;
  p.snap_spacing = std::isnormal(snap) ? power_of_two_at_most(snap) : 0.0;
  // fTetWild's choice: at least one target edge length of room around the
  // input, so that the tets between surface and box can reach the target
  // size, and at least 2 epsilon, so that no envelope ever touches the box.
  p.box_margin = std::max(p.edge_length, 2.0 * p.epsilon);
  p.box_min = p.input_min - Vec3d::Constant(p.box_margin);
  p.box_max = p.input_max + Vec3d::Constant(p.box_margin);
  return p;
}

}  // namespace mr::tetmesh
