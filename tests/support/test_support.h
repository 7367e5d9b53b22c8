#pragma once
// Models built in code and small helpers shared by the tests.

#include <mr/core/tet_mesh.h>
#include <mr/core/triangle_soup.h>

#include <filesystem>
#include <iosfwd>
#include <sstream>
#include <string>
#include <vector>

namespace mr::test {

/// Axis-aligned cube [lo, hi]^3, 8 vertices, 12 outward triangles.
TriangleSoup cube_soup(double lo = 0.0, double hi = 1.0);

/// Three triangles sharing one edge (non-manifold), plus a duplicated face, a
/// zero-area face and an isolated vertex: everything a halfedge import loses.
TriangleSoup non_manifold_soup();

/// Unit cube split into 6 positively oriented tets (8 vertices), labels 1..6.
TetMesh cube_tets();

/// Kuhn subdivision of the grid of cells^3 cubes of side `step` from
/// (lo, lo, lo): every cell split into 6 positive tets around its main
/// diagonal, so neighbouring cells agree on their shared faces. Vertex
/// (i, j, k) has index (k * (cells + 1) + j) * (cells + 1) + i.
TetMesh kuhn_grid(double lo, double step, int cells);

/// tests/data (fixtures and fuzz regression files) and tests/tools (the npm tools the setup script
/// installs) of the source tree.
std::filesystem::path data_dir();
std::filesystem::path tools_dir();

/// A fresh empty directory for one test, removed when the object dies.
class TempDir {
 public:
  explicit TempDir(const std::string& name);
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& file) const { return path_ / file; }
  /// Names of the files now in the directory, sorted.
  std::vector<std::string> files() const;

 private:
  std::filesystem::path path_;
};

void write_text(const std::filesystem::path& path, const std::string& text);
void write_bytes(const std::filesystem::path& path, const std::vector<char>& bytes);

/// Runs a tool in-process; returns the exit code and fills out/err.
struct ToolRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};
/// The signature every tool's in-process entry point has (tools/*/NAME.h).
using ToolMain = int (*)(const std::vector<std::string>&, std::ostream&, std::ostream&);

/// Runs a tool in-process, capturing its exit code and both streams.
ToolRun run_tool(ToolMain tool, const std::vector<std::string>& args);
ToolRun run_format_convert(const std::vector<std::string>& args);

/// Collects everything written to std::cerr and std::clog while it lives
/// (OpenMesh's omerr() and omlog() write to std::cerr), restoring both after.
class CapturedStderr {
 public:
  CapturedStderr();
  ~CapturedStderr();
  CapturedStderr(const CapturedStderr&) = delete;
  CapturedStderr& operator=(const CapturedStderr&) = delete;
  std::string text() const { return buffer_.str(); }

 private:
  std::ostringstream buffer_;
  std::streambuf* cerr_;
  std::streambuf* clog_;
};

/// Signed volume enclosed by a closed, consistently oriented soup.
double enclosed_volume(const TriangleSoup& soup);
double tet_volume(const TetMesh& mesh);

}  // namespace mr::test
