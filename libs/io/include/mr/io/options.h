#pragma once
// Options for reading and writing meshes. User inputs only, with defaults;
// each plugin reads the part that concerns it.

#include <mr/core/coordinate_grid.h>

#include <filesystem>
#include <optional>
#include <string>

namespace mr::io {

/// Level set to mesh (reading an OpenVDB file as a surface).
struct LevelSetReadOptions {
  double isovalue = 0.0;    ///< which level to extract, in world units
  double adaptivity = 0.0;  ///< 0 = uniform triangles, 1 = most simplified
};

struct ReadOptions {
  /// Format name ("stl", "glb", "msh", ...) overriding the file extension; "" = by extension.
  std::string format;
  LevelSetReadOptions level_set;
};

/// Mesh to narrow-band level set (writing a surface as an OpenVDB file).
struct LevelSetWriteOptions {
  double voxel_size = 0.0;  ///< absolute; 0 = bounding-box diagonal / 256
  double half_width = 3.0;  ///< narrow band half width, in voxels
};

/// Draco compression, for .drc files and for GLB/glTF with
/// KHR_draco_mesh_compression. Quantization in bits per component.
struct DracoOptions {
  bool compress_gltf = false;  ///< write glTF/GLB meshes with KHR_draco_mesh_compression
  int position_bits = 16;
  int normal_bits = 10;
  int uv_bits = 12;
  int color_bits = 8;
  int speed = 3;  ///< 0 = smallest output, 10 = fastest
  /// Explicit position quantization (origin, range and bits; overrides
  /// position_bits). Unset: Draco derives it from the positions' bounds.
  /// A writer that rounds positions onto a grid first sets the grid's own.
  std::optional<CoordinateGrid::Quantization> position_grid;
};

/// The grid Draco stores positions inside [lo, hi] on: options.position_grid
/// if set, else position_bits over that box.
inline CoordinateGrid draco_position_grid(const DracoOptions& options, const Vec3d& lo, const Vec3d& hi) {
  return options.position_grid ? CoordinateGrid::quantized(*options.position_grid)
                               : CoordinateGrid::quantized_over(lo, hi, options.position_bits);
}

struct WriteOptions {
  /// Format name overriding the file extension; "" = by extension.
  std::string format;
  /// Binary encoding where the format has both (STL, PLY, MSH). ASCII if false.
  bool binary = true;
  /// MSH version to write: "4.1" or "2.2".
  std::string msh_version = "4.1";
  DracoOptions draco;
  /// glTF/GLB without Draco: the grid positions were rounded onto (float32,
  /// or float32 about an origin, which the writer then stores positions
  /// relative to, the origin becoming the node's translation). Unset:
  /// CoordinateGrid::float32_over the positions' box.
  std::optional<CoordinateGrid> gltf_position_grid;
  LevelSetWriteOptions level_set;
  /// The file being written, set by write_surface (writers are handed a
  /// temporary path): companions are named after it (OBJ's .mtl, textures).
  std::filesystem::path destination;
};

}  // namespace mr::io
