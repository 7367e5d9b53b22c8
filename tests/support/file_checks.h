#pragma once
// Helpers shared by the format tests: reading a written file back, round
// trips through a registry, and the bad-input check run on every hostile file.

#include "test_support.h"

#include <mr/io/mesh_io.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

namespace mr::test {

using PositionTriple = std::array<std::array<double, 3>, 3>;

/// Each face of `soup` as its corners' positions, sorted: faces comparable
/// across files and vertex orders.
inline std::multiset<PositionTriple> position_triples(const TriangleSoup& soup) {
  std::multiset<PositionTriple> out;
  for (const Triangle& t : soup.triangles) {
    PositionTriple c;
    for (std::size_t i = 0; i < 3; ++i)
      c[i] = {soup.positions[t[i]].x(), soup.positions[t[i]].y(), soup.positions[t[i]].z()};
    std::sort(c.begin(), c.end());
    out.insert(c);
  }
  return out;
}

inline std::vector<char> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::string read_text(const std::filesystem::path& path) {
  const std::vector<char> bytes = read_bytes(path);
  return {bytes.begin(), bytes.end()};
}

/// Writes `text` as `name` in a fresh folder and returns what `read` makes of it.
template <class Read>
auto read_written(const std::string& name, const std::string& text, const Read& read) {
  TempDir dir("read_written");
  write_text(dir / name, text);
  return read(dir / name);
}

/// Writes `soup` to `path` through `registry`, then reads it back.
inline TriangleSoup round_trip(const io::Registry& registry, const TriangleSoup& soup,
                               const std::filesystem::path& path, const io::WriteOptions& options = {}) {
  io::write_surface(registry, soup, path, options);
  return io::read_surface(registry, path);
}

inline TetMesh round_trip(const io::Registry& registry, const TetMesh& mesh,
                          const std::filesystem::path& path, const io::WriteOptions& options = {}) {
  io::write_volume(registry, mesh, path, options);
  return io::read_volume(registry, path);
}

/// Runs format-convert from `input` to `output_name` in the same folder and
/// checks that the input is refused as bad: exit code 2 within 2 seconds, a
/// message with the input's path and `problem`, and the folder left as it was
/// (no output, no temporary file).
inline void expect_rejected(const std::filesystem::path& input, const std::string& problem,
                            const std::string& output_name = "out.ply") {
  const std::filesystem::path folder = input.parent_path(), output = folder / output_name;
  const auto folder_files = [&folder] {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
      names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  };
  const std::vector<std::string> before = folder_files();
  const auto start = std::chrono::steady_clock::now();
  const ToolRun run = run_format_convert({input.string(), output.string()});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  INFO("stderr: " << run.err);
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Contains(input.string()));
  CHECK_THAT(run.err, Catch::Contains(problem));
  CHECK_FALSE(std::filesystem::exists(output));
  CHECK(seconds < 2.0);
  CHECK(folder_files() == before);
}

/// Writes `text` as `name` in a fresh folder, then expect_rejected.
inline void expect_text_rejected(const std::string& name, const std::string& text, const std::string& problem,
                                 const std::string& output_name = "out.ply") {
  TempDir dir("bad_input");
  write_text(dir / name, text);
  expect_rejected(dir / name, problem, output_name);
}

}  // namespace mr::test
