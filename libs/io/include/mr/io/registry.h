#pragma once
// The format registry: plugins register one Format per file format; the I/O
// core picks a format by file extension or by an explicit name. There is no
// global registry: callers build one (see mr/io/default_registry.h).

#include <mr/core/coordinate_grid.h>
#include <mr/core/scalar_field.h>
#include <mr/core/tet_mesh.h>
#include <mr/core/triangle_soup.h>
#include <mr/io/options.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace mr::io {

enum class MeshKind { surface, volume };

/// One file format. A reader or writer that the format lacks is left empty.
/// Readers throw mr::InputError naming the file on anything they cannot read;
/// writers throw mr::RunError. A writer is handed a temporary path with the
/// destination's extension; the core renames it into place on success.
struct Format {
  std::string name;                     ///< short unique name, e.g. "stl"
  std::vector<std::string> extensions;  ///< lower case with dot, e.g. {".stl"}
  MeshKind kind = MeshKind::surface;
  std::string description;

  std::function<TriangleSoup(const std::filesystem::path&, const ReadOptions&)> read_surface;
  std::function<void(const TriangleSoup&, const std::filesystem::path&, const WriteOptions&)> write_surface;
  std::function<TetMesh(const std::filesystem::path&, const ReadOptions&)> read_volume;
  std::function<void(const TetMesh&, const std::filesystem::path&, const WriteOptions&)> write_volume;

  /// Readers of a file's bytes already in memory; `name` stands for the file
  /// in error messages (and locates the files a format may refer to, such as
  /// a glTF's external buffers). Registry::add derives read_surface and
  /// read_volume from them when those are left empty.
  std::function<TriangleSoup(std::string_view bytes, const std::string& name, const ReadOptions&)>
      read_surface_bytes;
  std::function<TetMesh(std::string_view bytes, const std::string& name, const ReadOptions&)>
      read_volume_bytes;

  /// The grid this format stores surface positions on when written with
  /// `options`, for positions inside [lo, hi]. Empty: every double is stored
  /// exactly (the default).
  std::function<CoordinateGrid(const WriteOptions&, const Vec3d& lo, const Vec3d& hi)> position_grid;
  /// Reader of a scalar field sampled on a grid (a float grid of a .vdb
  /// file), for `tetrahedralize --sizing`; empty for formats without one.
  /// A tet mesh's node fields are read with read_volume instead.
  std::function<std::shared_ptr<const ScalarField>(const std::filesystem::path&)> read_field;

  bool can_read() const { return read_surface || read_volume; }
  bool can_write() const { return write_surface || write_volume; }
};

class Registry {
 public:
  /// Adds a format; throws std::logic_error if its name or an extension is taken.
  /// A format with a bytes reader but no path reader gets one that reads the whole file.
  void add(Format format);

  /// The format named `name`, or nullptr.
  const Format* by_name(const std::string& name) const;
  /// The format for the extension of `path` (case-insensitive), or nullptr.
  const Format* by_extension(const std::filesystem::path& path) const;
  /// by_name(explicit_name) if it is not empty, else by_extension(path);
  /// throws InputError (for reading) or UsageError (for writing) when none fits.
  const Format& resolve_for_read(const std::filesystem::path& path, const std::string& explicit_name) const;
  const Format& resolve_for_write(const std::filesystem::path& path, const std::string& explicit_name) const;

  const std::vector<Format>& formats() const { return formats_; }

 private:
  std::vector<Format> formats_;
};

}  // namespace mr::io
