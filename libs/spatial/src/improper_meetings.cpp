#include <mr/spatial/improper_meetings.h>

#include <mr/kernel/intersections.h>
#include <mr/spatial/box_grid.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <utility>

namespace mr::spatial {
namespace {

std::pair<Vec3d, Vec3d> box_of(const std::array<Vec3d, 3>& p) {
  return {p[0].cwiseMin(p[1]).cwiseMin(p[2]), p[0].cwiseMax(p[1]).cwiseMax(p[2])};
}

// Cells about twice the mean edge: a face then spans few cells.
double cell_size(const TriangleSoup& soup) {
  double sum = 0.0;
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const std::array<Vec3d, 3> p = soup.corners(f);
    sum += (p[1] - p[0]).norm() + (p[2] - p[1]).norm() + (p[0] - p[2]).norm();
  }
  const double mean = sum / (3.0 * static_cast<double>(std::max<std::size_t>(soup.triangles.size(), 1)));
  return std::max(2.0 * mean, 1e-300);
}

}  // namespace

std::vector<std::uint8_t> faces_meeting_others(const TriangleSoup& soup, std::span<const std::uint8_t> asked,
                                               std::span<const std::uint8_t> skip) {
  const auto skipped = [&](std::size_t f) { return !skip.empty() && skip[f]; };
  BoxGrid grid(bounding_box(soup).min(), cell_size(soup));
  for (std::size_t f = 0; f < soup.triangles.size(); ++f)
    if (!skipped(f)) {
      const auto [lo, hi] = box_of(soup.corners(f));
      grid.insert(static_cast<std::uint32_t>(f), lo, hi);
    }
  std::vector<std::uint8_t> meets(soup.triangles.size(), 0);
  tbb::parallel_for(std::size_t(0), soup.triangles.size(), [&](std::size_t f) {
    if (skipped(f) || (!asked.empty() && !asked[f])) return;
    const std::array<Vec3d, 3> p = soup.corners(f);
    const auto [lo, hi] = box_of(p);
    std::vector<std::uint32_t> near;
    grid.query(lo, hi, near);
    for (std::uint32_t g : near) {
      if (g == f) continue;
      const std::array<Vec3d, 3> q = soup.corners(g);
      if (intersect_triangles(p[0], p[1], p[2], q[0], q[1], q[2]).improper()) {
        meets[f] = 1;
        return;
      }
    }
  });
  return meets;
}

}  // namespace mr::spatial
