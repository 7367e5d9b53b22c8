// Replays every file under tests/data/fuzz/<target>/ through the entry point
// of fuzz target <target> (fuzz/fuzz_entry.h, fuzz/meshrepair_entry.h), as
// scripts/fuzz.sh found it: each once crashed a reader or the pipeline, or
// made a sanitizer report. Passing is a mesh or an InputError naming the
// input (for meshrepair: exit 0 or 2), without a crash or sanitizer report.

#include "fuzz_entry.h"
#include "meshrepair_entry.h"
#include "test_support.h"

#include <mr/io/default_registry.h>
#include <mr/io/file_bytes.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>

using namespace mr;

namespace {

const std::filesystem::path fuzz_data_dir = test::data_dir() / "fuzz";

std::vector<std::filesystem::path> sorted_entries(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> entries;
  if (std::filesystem::is_directory(dir))
    for (const auto& entry : std::filesystem::directory_iterator(dir)) entries.push_back(entry.path());
  std::sort(entries.begin(), entries.end());
  return entries;
}

}  // namespace

TEST_CASE("fuzz regression files read to a mesh or an InputError", "[fuzz]") {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("fuzz_regression");
  for (const std::filesystem::path& target_dir : sorted_entries(fuzz_data_dir)) {
    const std::string target = target_dir.filename().string();
    const char* format = fuzz::reader_format(target);
    INFO("target " << target);
    REQUIRE((format || target == "meshrepair"));
    if (format && !registry.by_name(format)) continue;  // a plugin this build lacks
    for (const std::filesystem::path& file : sorted_entries(target_dir)) {
      INFO("file " << file.string());
      const std::vector<char> bytes = io::read_file_bytes(file);
      const std::string_view view(bytes.data(), bytes.size());
      if (format)
        CHECK_NOTHROW(fuzz::read_as(registry, format, view));
      else
        CHECK_NOTHROW(fuzz::run_meshrepair(registry, view, dir.path()));
    }
  }
}

TEST_CASE("a mesh read from memory is the mesh read from the file", "[fuzz][io]") {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("read_bytes");
  const TriangleSoup cube = test::cube_soup();
  for (const io::Format& format : registry.formats()) {
    if (!format.write_surface || !format.read_surface_bytes) continue;
    INFO("format " << format.name);
    const std::filesystem::path path = dir / ("cube" + format.extensions.front());
    io::write_surface(registry, cube, path);
    const TriangleSoup from_file = io::read_surface(registry, path);
    const std::vector<char> bytes = io::read_file_bytes(path);
    const TriangleSoup from_bytes =
        io::read_surface_bytes(registry, std::string_view(bytes.data(), bytes.size()), path.string());
    CHECK(from_bytes.positions == from_file.positions);
    CHECK(from_bytes.triangles == from_file.triangles);
    CHECK_THROWS_AS(io::read_surface_bytes(registry, {}, path.string()), InputError);
  }
  const std::filesystem::path msh = dir / "cube.msh";
  io::write_volume(registry, test::cube_tets(), msh);
  const std::vector<char> bytes = io::read_file_bytes(msh);
  const TetMesh from_bytes =
      io::read_volume_bytes(registry, std::string_view(bytes.data(), bytes.size()), msh.string());
  CHECK(from_bytes.tets == io::read_volume(registry, msh).tets);
  CHECK_THROWS_AS(io::read_volume_bytes(registry, "x", "cube.vtu"), UsageError);
}
