#include <mr/core/boundary.h>
#include <mr/core/errors.h>
#include <mr/io/atomic_file.h>
#include <mr/io/mesh_io.h>

#include <new>
#include <system_error>

namespace mr::io {
namespace {

// Checks what every reader needs before it opens the file.
void check_readable(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw InputError(path.string(), "no such file");
  if (std::filesystem::is_directory(status))
    throw InputError(path.string(), "is a directory, not a mesh file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path.string(), "cannot read the file size: " + ec.message());
  if (size == 0) throw InputError(path.string(), "the file is empty");
}

void check_output_path(const std::filesystem::path& path) {
  if (path.empty()) throw UsageError("empty output path");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw UsageError(path.string() + " is a directory");
}

// What a reader returns must be consistent (indices in range, finite
// coordinates) and hold something to work on: an input with nothing is a bad
// input, not an empty result (random bytes named .obj parse as an OBJ
// without a single face).
void check_surface(const TriangleSoup& soup, const std::string& name) {
  if (std::string problem = find_soup_inconsistency(soup); !problem.empty()) throw InputError(name, problem);
  if (soup.triangles.empty()) throw InputError(name, "no triangles found");
}

void check_volume(const TetMesh& mesh, const std::string& name) {
  if (std::string problem = find_tet_mesh_inconsistency(mesh); !problem.empty())
    throw InputError(name, problem);
  if (mesh.tets.empty()) throw InputError(name, "no tets found");
}

[[noreturn]] void throw_no_bytes_reader(const Format& format) {
  throw UsageError("format " + format.name + " cannot be read from memory");
}

// Runs a format's reader. Our own errors pass through; anything else a
// library throws (a parser's exception, out of memory on a hostile size)
// becomes an InputError naming the file, never a bare library message.
template <class Read>
auto read_guarded(const Format& format, const std::string& name, const Read& read) {
  try {
    return read();
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw InputError(name, "cannot be read as " + format.name + ": it needs more memory than is available");
  } catch (const std::exception& e) {
    throw InputError(name, "cannot be read as " + format.name + ": " + library_error_text(e));
  }
}

// The same for a writer: a library's exception becomes a RunError naming the
// destination (the writer itself only sees the temporary path).
void write_guarded(const Format& format, const std::filesystem::path& path,
                   const std::function<void(const std::filesystem::path&)>& write) {
  try {
    write_atomically(path, write);
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw RunError("cannot write " + path.string() + " as " + format.name + ": out of memory");
  } catch (const std::exception& e) {
    throw RunError("cannot write " + path.string() + " as " + format.name + ": " + library_error_text(e));
  }
}

}  // namespace

bool is_volume_format(const Registry& registry, const std::filesystem::path& path,
                      const std::string& explicit_format) {
  // Write-only formats (VTU) count too: tools ask this of their outputs.
  const Format* format =
      explicit_format.empty() ? registry.by_extension(path) : registry.by_name(explicit_format);
  if (!format) format = &registry.resolve_for_read(path, explicit_format);  // throws the usual message
  return format->kind == MeshKind::volume;
}

TetMesh read_volume(const Registry& registry, const std::filesystem::path& path, const ReadOptions& options) {
  const Format& format = registry.resolve_for_read(path, options.format);
  if (!format.read_volume)
    throw InputError(path.string(), "is a surface format (" + format.name + "), not a volume mesh");
  check_readable(path);
  TetMesh mesh = read_guarded(format, path.string(), [&] { return format.read_volume(path, options); });
  check_volume(mesh, path.string());
  return mesh;
}

TriangleSoup read_surface(const Registry& registry, const std::filesystem::path& path,
                          const ReadOptions& options) {
  const Format& format = registry.resolve_for_read(path, options.format);
  if (!format.read_surface) return extract_boundary(read_volume(registry, path, options));
  check_readable(path);
  TriangleSoup soup = read_guarded(format, path.string(), [&] { return format.read_surface(path, options); });
  check_surface(soup, path.string());
  return soup;
}

TetMesh read_volume_bytes(const Registry& registry, std::string_view bytes, const std::string& name,
                          const ReadOptions& options) {
  const Format& format = registry.resolve_for_read(name, options.format);
  if (!format.read_volume)
    throw InputError(name, "is a surface format (" + format.name + "), not a volume mesh");
  if (!format.read_volume_bytes) throw_no_bytes_reader(format);
  if (bytes.empty()) throw InputError(name, "the file is empty");
  TetMesh mesh = read_guarded(format, name, [&] { return format.read_volume_bytes(bytes, name, options); });
  check_volume(mesh, name);
  return mesh;
}

TriangleSoup read_surface_bytes(const Registry& registry, std::string_view bytes, const std::string& name,
                                const ReadOptions& options) {
  const Format& format = registry.resolve_for_read(name, options.format);
  if (!format.read_surface) return extract_boundary(read_volume_bytes(registry, bytes, name, options));
  if (!format.read_surface_bytes) throw_no_bytes_reader(format);
  if (bytes.empty()) throw InputError(name, "the file is empty");
  TriangleSoup soup =
      read_guarded(format, name, [&] { return format.read_surface_bytes(bytes, name, options); });
  check_surface(soup, name);
  return soup;
}

namespace {

const Format& surface_format_for_write(const Registry& registry, const std::filesystem::path& path,
                                       const WriteOptions& options) {
  const Format& format = registry.resolve_for_write(path, options.format);
  if (!format.write_surface) throw UsageError("format " + format.name + " holds volume meshes, not surfaces");
  return format;
}

}  // namespace

CoordinateGrid surface_position_grid(const Registry& registry, const std::filesystem::path& path,
                                     const WriteOptions& options, const Vec3d& lo, const Vec3d& hi) {
  const Format& format = surface_format_for_write(registry, path, options);
  return format.position_grid ? format.position_grid(options, lo, hi) : CoordinateGrid::doubles();
}

void write_surface(const Registry& registry, const TriangleSoup& soup, const std::filesystem::path& path,
                   const WriteOptions& options, const WrittenFileCheck& check) {
  const Format& format = surface_format_for_write(registry, path, options);
  if (std::string problem = find_soup_inconsistency(soup); !problem.empty())
    throw RunError("refusing to write an inconsistent mesh to " + path.string() + ": " + problem);
  check_output_path(path);
  WriteOptions named = options;
  named.destination = path;
  write_guarded(format, path, [&](const std::filesystem::path& temp) {
    format.write_surface(soup, temp, named);
    if (check) check(temp);
  });
}

void write_volume(const Registry& registry, const TetMesh& mesh, const std::filesystem::path& path,
                  const WriteOptions& options) {
  const Format& format = registry.resolve_for_write(path, options.format);
  if (!format.write_volume) throw UsageError("format " + format.name + " holds surfaces, not volume meshes");
  if (std::string problem = find_tet_mesh_inconsistency(mesh); !problem.empty())
    throw RunError("refusing to write an inconsistent mesh to " + path.string() + ": " + problem);
  check_output_path(path);
  write_guarded(format, path,
                [&](const std::filesystem::path& temp) { format.write_volume(mesh, temp, options); });
}

}  // namespace mr::io
