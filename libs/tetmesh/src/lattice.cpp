#include <mr/tetmesh/background_mesh.h>

#include <mr/core/errors.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace mr::tetmesh {
namespace {

constexpr double kMaxLatticePoints = 1e8;

std::array<long, 3> intervals_per_axis(const Vec3d& box_min, const Vec3d& box_max, double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) throw UsageError("lattice spacing must be positive");
  std::array<long, 3> n{};
  double total = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double extent = box_max[axis] - box_min[axis];
    if (!(extent > 0.0)) throw UsageError("lattice: the box is empty");
    const double count = std::max(1.0, std::round(extent / spacing));
    total *= count + 1.0;
    if (total > kMaxLatticePoints)
      throw UsageError("lattice: more than 10^8 points; choose a larger spacing");
    n[axis] = static_cast<long>(count);
  }
  return n;
}

// Coordinate i of n intervals: the last one is exactly hi, so box faces are exact.
double lattice_coordinate(double lo, double hi, long i, long n) {
  return i == n ? hi : lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(n);
}

bool is_box_corner(const Vec3d& p, const Vec3d& box_min, const Vec3d& box_max) {
  for (int axis = 0; axis < 3; ++axis) {
    if (p[axis] != box_min[axis] && p[axis] != box_max[axis]) return false;
  }
  return true;
}

}  // namespace

BackgroundParameters background_parameters(const DerivedParameters& derived, int threads) {
  BackgroundParameters p;
  p.box_min = derived.box_min;
  p.box_max = derived.box_max;
  p.lattice_spacing = derived.lattice_spacing;
  p.lattice_clearance = derived.lattice_clearance;
  p.threads = threads;
  return p;
}

std::vector<Vec3d> lattice_points(const Vec3d& box_min, const Vec3d& box_max, double spacing) {
  const std::array<long, 3> n = intervals_per_axis(box_min, box_max, spacing);
  std::vector<Vec3d> points;
  points.reserve(static_cast<std::size_t>((n[0] + 1) * (n[1] + 1) * (n[2] + 1)));
  for (long i = 0; i <= n[0]; ++i) {
    const double x = lattice_coordinate(box_min.x(), box_max.x(), i, n[0]);
    for (long j = 0; j <= n[1]; ++j) {
      const double y = lattice_coordinate(box_min.y(), box_max.y(), j, n[1]);
      for (long k = 0; k <= n[2]; ++k) {
        points.emplace_back(x, y, lattice_coordinate(box_min.z(), box_max.z(), k, n[2]));
      }
    }
  }
  return points;
}

std::vector<Vec3d> voxel_stuffing_points(const Vec3d& box_min, const Vec3d& box_max, double spacing,
                                         double clearance, const spatial::AabbTree& tree) {
  const std::vector<Vec3d> all = lattice_points(box_min, box_max, spacing);
  std::vector<char> keep(all.size(), 0);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, all.size(), 256), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          keep[i] = !is_box_corner(all[i], box_min, box_max) && !tree.any_within(all[i], clearance);
        }
      });
  std::vector<Vec3d> kept;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (keep[i]) kept.push_back(all[i]);
  }
  return kept;
}

}  // namespace mr::tetmesh
