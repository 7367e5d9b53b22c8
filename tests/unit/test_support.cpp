#include "test_support.h"

#include "format_convert.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

namespace mr::test {

// The folders come from this file's compile definitions only (tests/CMakeLists.txt): absolute
// paths on a compiler's command line keep ccache from sharing objects between checkouts.
std::filesystem::path data_dir() { return MR_TEST_DATA_DIR; }
std::filesystem::path tools_dir() { return MR_TEST_TOOLS_DIR; }

TriangleSoup cube_soup(double lo, double hi) {
  TriangleSoup soup;
  for (int i = 0; i < 8; ++i) soup.positions.emplace_back(i & 1 ? hi : lo, i & 2 ? hi : lo, i & 4 ? hi : lo);
  soup.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return soup;
}

TriangleSoup non_manifold_soup() {
  TriangleSoup soup;
  // Vertex 5 lies on edge 0-1 (a zero-area face); vertex 6 is isolated.
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0.5, 0, 0}, {5, 5, 5}};
  soup.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4},  // three faces on edge 0-1
                    {0, 1, 2},                        // a duplicate
                    {0, 1, 5},                        // zero area
                    {2, 2, 4}};                       // a repeated index
  return soup;
}

TetMesh cube_tets() {
  TetMesh mesh;
  for (int i = 0; i < 8; ++i) mesh.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  // Kuhn subdivision along the diagonal 0-7; orientation fixed below.
  mesh.tets = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  for (Tet& t : mesh.tets) {
    const Vec3d &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]],
                &d = mesh.positions[t[3]];
    if ((b - a).cross(c - a).dot(d - a) < 0) std::swap(t[1], t[2]);
  }
  mesh.tet_labels = {1, 2, 3, 4, 5, 6};
  return mesh;
}

TetMesh kuhn_grid(double lo, double step, int cells) {
  TetMesh grid;
  const int n = cells + 1;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) grid.positions.emplace_back(lo + i * step, lo + j * step, lo + k * step);
  const auto id = [n](int i, int j, int k) { return Index((k * n + j) * n + i); };
  const TetMesh cell = cube_tets();
  for (int k = 0; k < cells; ++k)
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i)
        for (const Tet& t : cell.tets) {
          Tet g{};
          for (int c = 0; c < 4; ++c) {
            const Vec3d& p = cell.positions[t[c]];
            g[c] = id(i + int(p.x()), j + int(p.y()), k + int(p.z()));
          }
          grid.tets.push_back(g);
        }
  return grid;
}

TempDir::TempDir(const std::string& name) {
  static std::mt19937_64 rng(std::random_device{}());
  path_ = std::filesystem::temp_directory_path() / ("mr_test_" + name + "_" + std::to_string(rng()));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::vector<std::string> TempDir::files() const {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(path_))
    names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

void write_bytes(const std::filesystem::path& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

ToolRun run_tool(ToolMain tool, const std::vector<std::string>& args) {
  std::ostringstream out, err;
  ToolRun run;
  run.exit_code = tool(args, out, err);
  run.out = out.str();
  run.err = err.str();
  return run;
}

CapturedStderr::CapturedStderr()
    : cerr_(std::cerr.rdbuf(buffer_.rdbuf())), clog_(std::clog.rdbuf(buffer_.rdbuf())) {}

CapturedStderr::~CapturedStderr() {
  std::cerr.rdbuf(cerr_);
  std::clog.rdbuf(clog_);
}

ToolRun run_format_convert(const std::vector<std::string>& args) {
  return run_tool(tools::format_convert, args);
}

double enclosed_volume(const TriangleSoup& soup) {
  double six_volume = 0;
  for (const Triangle& t : soup.triangles)
    six_volume += soup.positions[t[0]].dot(soup.positions[t[1]].cross(soup.positions[t[2]]));
  return six_volume / 6.0;
}

double tet_volume(const TetMesh& mesh) {
  double six_volume = 0;
  for (const Tet& t : mesh.tets) {
    const Vec3d& a = mesh.positions[t[0]];
    six_volume += (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).dot(mesh.positions[t[3]] - a);
  }
  return six_volume / 6.0;
}

}  // namespace mr::test
