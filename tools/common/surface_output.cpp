#include "surface_output.h"

#include <mr/check/surface_check.h>
#include <mr/core/errors.h>
#include <mr/core/weld.h>
#include <mr/io/mesh_io.h>

#include <algorithm>
#include <cstdint>
#include <iomanip>
#include <sstream>
#include <utility>
#include <vector>

namespace mr::tools {

int draco_position_bits_for(double extent, double epsilon) {
  for (int bits = 12; bits < 30; ++bits)
    if (extent / double((std::int64_t{1} << bits) - 1) <= epsilon / 64.0) return bits;
  return 30;
}

namespace {
// Draco computes in float, whose significand has 24 bits: a finer grid has
// more levels across the model than floats there, and most of its values
// would not be stored as they are.
constexpr int kMostFinerDracoBits = 24;
}  // namespace

std::optional<CoordinateGrid> finer_draco_grid(const io::Registry& registry, const std::string& path,
                                               const io::WriteOptions& options, const Vec3d& lo,
                                               const Vec3d& hi, const CoordinateGrid& refused) {
  if (refused.kind() != CoordinateGrid::Kind::quantized || refused.quantization().bits >= kMostFinerDracoBits)
    return std::nullopt;
  io::WriteOptions finer = options;
  finer.draco.position_bits = std::min(kMostFinerDracoBits, refused.quantization().bits + 2);
  finer.draco.position_grid.reset();
  return io::surface_position_grid(registry, path, finer, lo, hi);
}

void write_on_grid(io::WriteOptions& options, const CoordinateGrid& grid) {
  if (grid.kind() == CoordinateGrid::Kind::float32 || grid.kind() == CoordinateGrid::Kind::float32_about)
    options.gltf_position_grid = grid;
  if (grid.kind() != CoordinateGrid::Kind::quantized) return;
  options.draco.position_bits = grid.quantization().bits;
  options.draco.position_grid = grid.quantization();
}

void require_grid_holds(const CoordinateGrid& grid, const std::string& path, const Eigen::AlignedBox3d& box,
                        double epsilon) {
  const double spacing = grid.spacing_over(box.min(), box.max());
  if (spacing <= epsilon) return;
  const double farthest = std::max(box.min().cwiseAbs().maxCoeff(), box.max().cwiseAbs().maxCoeff());
  const bool far = farthest > 1e3 * box.diagonal().norm();
  std::ostringstream why;
  why << std::setprecision(3) << path << ": " << grid.name() << " positions are " << spacing
      << " apart where the model lies (coordinates up to " << farthest << "), more than epsilon (" << epsilon
      << "), so the surface cannot be written within epsilon of the input; write .obj, .off or .ply "
         "(doubles)";
  if (far)
    why << ", or move the model nearer to the origin";
  else if (grid.kind() == CoordinateGrid::Kind::quantized)
    why << ", or scale the model up (Draco's grid spans at least 1e-6)";
  throw UsageError(why.str());
}

SurfaceWrite write_watertight_surface(const io::Registry& registry, TriangleSoup surface,
                                      const std::string& path, io::WriteOptions options,
                                      bool finer_draco_grid, const SurfaceDressing& dress) {
  SurfaceWrite result;
  result.watertight = true;
  const Eigen::AlignedBox3d box = bounding_box(surface);
  const CoordinateGrid grid = io::surface_position_grid(registry, path, options, box.min(), box.max());
  repair::FinerGrid finer;
  if (finer_draco_grid)
    finer = [&](const CoordinateGrid& refused) {
      return tools::finer_draco_grid(registry, path, options, box.min(), box.max(), refused);
    };
  const repair::GridRounding rounded = repair::round_to_grid_or_finer(surface, grid, finer);
  write_on_grid(options, rounded.grid);
  result.rounding = rounded.stats;
  io::write_surface(registry, dress ? dress(surface, rounded.grid) : surface, path, options,
                    check::watertight_file_check(registry, path, &result.written));
  return result;
}

SurfaceWrite write_surface_keeping_watertight(const io::Registry& registry, TriangleSoup surface,
                                              const std::string& path, io::WriteOptions options,
                                              bool finer_draco_grid) {
  if (surface.triangles.empty() || !check::check_surface(surface).watertight()) {
    io::write_surface(registry, surface, path, options);
    return {};
  }
  // Kept watertight, but not by moving it further than meshrepair's default
  // epsilon: a unit cube 1e9 from the origin became 64 units wide. (Draco
  // bits the user chose are taken as the precision asked for.)
  const Eigen::AlignedBox3d box = bounding_box(surface);
  const CoordinateGrid grid = io::surface_position_grid(registry, path, options, box.min(), box.max());
  if (grid.kind() != CoordinateGrid::Kind::quantized || finer_draco_grid)
    require_grid_holds(grid, path, box, 1e-3 * box.diagonal().norm());
  std::vector<Index> welded_index;
  TriangleSoup welded = weld_identical_vertices(surface, welded_index);
  if (welded.positions.size() == surface.positions.size())
    return write_watertight_surface(registry, std::move(surface), path, std::move(options), finer_draco_grid);
  // Seams (UVs, normals) split positions: the welded surface is rounded and
  // every vertex of the original takes its position's place, unless the
  // rounding had to collapse vertices; then the welded surface is written.
  const std::size_t welded_vertices = welded.positions.size();
  return write_watertight_surface(registry, std::move(welded), path, std::move(options), finer_draco_grid,
                                  [&](const TriangleSoup& rounded, const CoordinateGrid&) {
                                    if (rounded.positions.size() != welded_vertices) return rounded;
                                    TriangleSoup out = surface;
                                    for (std::size_t v = 0; v < out.positions.size(); ++v)
                                      out.positions[v] = rounded.positions[welded_index[v]];
                                    return out;
                                  });
}

}  // namespace mr::tools
