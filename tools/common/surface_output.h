#pragma once
// Writing a surface so that what the user receives keeps what the doubles had.

#include <mr/check/written_file.h>
#include <mr/io/registry.h>
#include <mr/repair/round_to_grid.h>

#include <functional>
#include <optional>
#include <string>

namespace mr::tools {

/// The fewest Draco position bits (at least 12, at most 30) whose grid step
/// over `extent` is at most epsilon / 64: rounding then moves a surface by
/// far less than epsilon.
int draco_position_bits_for(double extent, double epsilon);

/// The Draco grid of two more bits (up to 24) than `refused`, for writing
/// positions inside [lo, hi] to `path` with `options`. Nothing when
/// `refused` is not a Draco grid or has 24 bits or more.
std::optional<CoordinateGrid> finer_draco_grid(const io::Registry& registry, const std::string& path,
                                               const io::WriteOptions& options, const Vec3d& lo,
                                               const Vec3d& hi, const CoordinateGrid& refused);

/// Sets `options` to write positions on `grid`: a Draco grid, or the
/// float32 grid (plain or about an origin) a glTF writer is to use.
void write_on_grid(io::WriteOptions& options, const CoordinateGrid& grid);

/// Throws mr::UsageError naming `path` when `grid` stores positions more
/// than `epsilon` apart somewhere in `box`: the file cannot hold a surface
/// there within epsilon (float32 a billion units from the origin, where
/// floats are 64 apart), and rounding onto it would merge the vertices.
void require_grid_holds(const CoordinateGrid& grid, const std::string& path, const Eigen::AlignedBox3d& box,
                        double epsilon);

struct SurfaceWrite {
  bool watertight = false;  ///< watertight in doubles, hence rounded and checked as written
  repair::GridRoundingStats rounding;
  check::WrittenFileReport written;  ///< of the written file, when watertight
};

/// Writes `surface` to `path`. A surface watertight in doubles (after
/// welding identical positions) goes onto the grid the format stores
/// (repair::round_to_grid on the welded surface, Draco's grid fixed here;
/// vertices split at seams keep their attributes unless rounding had to
/// collapse vertices) and the file is read back and checked before it is
/// renamed into place (mr::RunError if it is not watertight; mr::UsageError,
/// before any work, if the format's grid is coarser than 1e-3 of the
/// surface's bounding-box diagonal where it lies, unless it is a Draco grid
/// of bits the user chose: finer_draco_grid false); any other
/// surface (open, pinched, inward) is written as it is. Where no place on a Draco grid is
/// left for some vertex, the grid gets two more bits (up to 24) unless
/// `finer_draco_grid` is false (the user chose the bits).
SurfaceWrite write_surface_keeping_watertight(const io::Registry& registry, TriangleSoup surface,
                                              const std::string& path, io::WriteOptions options,
                                              bool finer_draco_grid = true);

/// What is written for a surface rounded onto the output's grid: the
/// surface itself, or a copy with more (e.g. attributes carried from the input).
using SurfaceDressing = std::function<TriangleSoup(const TriangleSoup& rounded, const CoordinateGrid& grid)>;

/// The same for a surface the caller knows to be watertight in doubles
/// (no check before rounding; the written file is still checked); `dress`,
/// when given, makes what is written from the rounded surface.
SurfaceWrite write_watertight_surface(const io::Registry& registry, TriangleSoup surface,
                                      const std::string& path, io::WriteOptions options,
                                      bool finer_draco_grid = true, const SurfaceDressing& dress = {});

}  // namespace mr::tools
