#include "surface_output.h"

#include <mr/check/surface_check.h>
#include <mr/io/mesh_io.h>

#include <mr/core/errors.h>

#include <algorithm>
#include <cstdint>

namespace mr::tools {

int draco_position_bits_for(double extent, double epsilon) {
  for (int bits = 12; bits < 30; ++bits)
    if (extent / double((std::int64_t{1} << bits) - 1) <= epsilon / 64.0) return bits;
  return 30;
}

SurfaceWrite write_surface_keeping_watertight(const io::Registry& registry, TriangleSoup surface,
                                              const std::string& path, io::WriteOptions options,
                                              bool finer_draco_grid) {
  SurfaceWrite result;
  result.watertight = !surface.triangles.empty() && check::check_surface(surface).watertight();
  if (!result.watertight) {
    io::write_surface(registry, surface, path, options);
    return result;
  }
  Vec3d lo = surface.positions.front(), hi = lo;
  for (const Vec3d& p : surface.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const TriangleSoup unrounded = surface;
  while (true) {
    const CoordinateGrid grid = io::surface_position_grid(registry, path, options, lo, hi);
    const bool quantized = grid.kind() == CoordinateGrid::Kind::quantized;
    if (quantized) options.draco.position_grid = grid.quantization();
    try {
      result.rounding = repair::round_to_grid(surface, grid);
      break;
    } catch (const RunError&) {
      if (!quantized || !finer_draco_grid || grid.quantization().bits >= 30) throw;
      options.draco.position_bits = std::min(30, grid.quantization().bits + 2);
      options.draco.position_grid.reset();
      surface = unrounded;
    }
  }
  io::write_surface(registry, surface, path, options, check::watertight_file_check(registry, path, &result.written));
  return result;
}

}  // namespace mr::tools
