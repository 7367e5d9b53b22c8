#pragma once
// Reading and writing meshes through a registry. These functions add what
// every format needs: the file must exist and not be empty, the result is
// checked for consistency (indices in range, finite coordinates) and must
// hold geometry (a triangle, or a tet for a volume), a library's exception
// becomes one of ours naming the file, and output is written to a temporary
// file renamed into place, so that a failed or interrupted write never leaves
// a half-written file.

#include <mr/io/registry.h>

namespace mr::io {

/// Reads a surface. A volume file is accepted too: its boundary is returned.
/// Throws InputError naming the file if it holds no triangle ("no triangles
/// found"; degenerate ones count) or, read as a volume, no tet.
TriangleSoup read_surface(const Registry& registry, const std::filesystem::path& path,
                          const ReadOptions& options = {});

/// Reads a volume mesh; throws InputError if `path` is a surface format or
/// the file holds no tet ("no tets found").
TetMesh read_volume(const Registry& registry, const std::filesystem::path& path,
                    const ReadOptions& options = {});

/// read_surface and read_volume for a file's bytes already in memory (an
/// upload, an archive member, a fuzzer's input). The format is
/// options.format, else the one for the extension of `name`, which messages
/// use as the file's name. Throws UsageError if that format has no reader
/// of bytes, and otherwise exactly what reading the same bytes from a file
/// named `name` throws.
TriangleSoup read_surface_bytes(const Registry& registry, std::string_view bytes, const std::string& name,
                                const ReadOptions& options = {});
TetMesh read_volume_bytes(const Registry& registry, std::string_view bytes, const std::string& name,
                          const ReadOptions& options = {});

/// True if the format chosen for `path` (or options.format) holds a volume mesh.
bool is_volume_format(const Registry& registry, const std::filesystem::path& path,
                      const std::string& explicit_format = {});

/// Checks a written file (handed its temporary path) and throws, with the
/// reason, when it breaks a promise; the output is then not renamed into place.
using WrittenFileCheck = std::function<void(const std::filesystem::path& written)>;

void write_surface(const Registry& registry, const TriangleSoup& soup, const std::filesystem::path& path,
                   const WriteOptions& options = {}, const WrittenFileCheck& check = {});

/// The grid on which the format chosen for `path` (or options.format) stores
/// the positions of a surface inside [lo, hi]. Throws like write_surface
/// when no surface format fits.
CoordinateGrid surface_position_grid(const Registry& registry, const std::filesystem::path& path,
                                     const WriteOptions& options, const Vec3d& lo, const Vec3d& hi);

void write_volume(const Registry& registry, const TetMesh& mesh, const std::filesystem::path& path,
                  const WriteOptions& options = {});

}  // namespace mr::io
