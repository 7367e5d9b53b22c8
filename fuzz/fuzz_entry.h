#pragma once
// The entry points the fuzz targets call, shared with the regression test
// (tests/unit/fuzz_regression_test.cpp) so that a saved crash replays
// exactly as it was found. Header-only: each fuzz target links only what
// its entry needs.
//
// A reader target hands its bytes to io::read_surface_bytes, or
// io::read_volume_bytes and then extract_boundary for a volume format, as a
// file named "fuzz<extension>" would be read. Passing is a mesh or an
// mr::InputError naming that file; any other exception escapes to the
// caller (libFuzzer reports it as a crash), and so do sanitizer reports.

#include <mr/core/boundary.h>
#include <mr/core/errors.h>
#include <mr/io/mesh_io.h>

#include <stdexcept>
#include <string>
#include <string_view>

namespace mr::fuzz {

/// A fuzz target of a reader: its name (the folder of its corpus, crash and
/// regression files) and the registry format it reads.
struct ReaderTarget {
  const char* name;
  const char* format;
};

/// STL and PLY have one reader each for both encodings; their two targets
/// differ in seeds and input sizes. MSH 2.2 and 4.1, ASCII and binary, are
/// one target: the reader dispatches on the header.
inline constexpr ReaderTarget reader_targets[] = {
    {"stl_binary", "stl"}, {"stl_ascii", "stl"},  {"obj", "obj"},    {"off", "off"},
    {"ply_ascii", "ply"},  {"ply_binary", "ply"}, {"gltf", "gltf"},  {"glb", "glb"},
    {"drc", "drc"},        {"msh", "msh"},        {"medit", "mesh"}, {"vdb", "vdb"},
};

/// The format read by the reader target `target`, or nullptr.
inline const char* reader_format(std::string_view target) {
  for (const ReaderTarget& t : reader_targets)
    if (target == t.name) return t.format;
  return nullptr;
}

enum class ReadOutcome { mesh, input_error };

/// Reads `bytes` as `format`. Throws std::logic_error for an InputError that
/// does not name the input, and lets every other exception through.
inline ReadOutcome read_as(const io::Registry& registry, const std::string& format, std::string_view bytes) {
  const io::Format* entry = registry.by_name(format);
  if (!entry) throw std::logic_error("format " + format + " is not in this build");
  const std::string name = "fuzz" + entry->extensions.front();
  io::ReadOptions options;
  options.format = format;
  try {
    if (entry->kind == io::MeshKind::volume) {
      const TetMesh mesh = io::read_volume_bytes(registry, bytes, name, options);
      const TriangleSoup boundary = extract_boundary(mesh);
      if (std::string problem = find_soup_inconsistency(boundary); !problem.empty())
        throw std::logic_error("the boundary of a mesh read is inconsistent: " + problem);
    } else {
      io::read_surface_bytes(registry, bytes, name, options);
    }
    return ReadOutcome::mesh;
  } catch (const InputError& e) {
    if (e.path() != name) throw std::logic_error("an InputError names '" + e.path() + "', not " + name);
    return ReadOutcome::input_error;
  }
}

}  // namespace mr::fuzz
