// Interoperability with Google's own command line tools (Debian package "draco").

#include "draco_test_support.h"

#include <mr/core/errors.h>
#include <mr/io/mesh_io.h>
#include <mr/plugins/draco_formats.h>

#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>

using namespace mr;
using namespace mr::draco_test;

namespace {

std::string require_tool(const std::string& name) {
  const std::string path = find_on_path(name);
  if (path.empty())
    FAIL(name << " not found on PATH: install the Debian package 'draco' (it provides draco_encoder and "
                 "draco_decoder), needed to check interoperability");
  return path;
}

void run_tool(const std::string& command, const std::filesystem::path& log) {
  const int status = std::system((command + " > '" + log.string() + "' 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream output;
  output << in.rdbuf();
  INFO(command << "\n" << output.str());
  REQUIRE(status == 0);
}

std::string quoted(const std::filesystem::path& path) {
  std::string text(1, '\'');
  text += path.string();
  text += '\'';
  return text;
}

std::size_t count_obj_faces(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::size_t faces = 0;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("f ", 0) == 0) ++faces;
  return faces;
}

std::size_t ply_face_count(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  for (std::string line; std::getline(in, line) && line.rfind("end_header", 0) != 0;)
    if (line.rfind("element face ", 0) == 0) return std::stoul(line.substr(13));
  return 0;
}

void write_ascii_ply(const TriangleSoup& soup, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "ply\nformat ascii 1.0\nelement vertex " << soup.num_vertices()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << soup.num_triangles()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  out.precision(9);
  for (const Vec3d& p : soup.positions) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const Triangle& t : soup.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

}  // namespace

TEST_CASE("draco_decoder reads the .drc files we write", "[draco]") {
  const std::string decoder = require_tool("draco_decoder");
  io::Registry registry;
  plugins::register_draco_formats(registry);
  test::TempDir dir("draco_interop_out");

  TriangleSoup cube = cube_with_attributes();
  cube.face_regions = {0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5};
  const TriangleSoup grid = make_grid(20, 10, 0.2);
  const std::vector<std::pair<std::string, TriangleSoup>> models = {
      {"cube", cube}, {"grid", grid}, {"non_manifold", test::non_manifold_soup()}};
  for (const auto& [name, soup] : models) {
    INFO(name);
    const auto drc = dir / (name + ".drc");
    io::write_surface(registry, soup, drc);
    run_tool(decoder + " -i " + quoted(drc) + " -o " + quoted(dir / (name + ".obj")), dir / "log.txt");
    CHECK(count_obj_faces(dir / (name + ".obj")) == soup.num_triangles());
    run_tool(decoder + " -i " + quoted(drc) + " -o " + quoted(dir / (name + ".ply")), dir / "log.txt");
    CHECK(ply_face_count(dir / (name + ".ply")) == soup.num_triangles());
  }
}

TEST_CASE("we read the .drc files draco_encoder writes", "[draco]") {
  const std::string encoder = require_tool("draco_encoder");
  io::Registry registry;
  plugins::register_draco_formats(registry);
  test::TempDir dir("draco_interop_in");
  const TriangleSoup grid = make_grid(20, 10, 0.2);
  write_ascii_ply(grid, dir / "grid.ply");

  for (const char* level : {"0", "7", "10"}) {
    INFO("compression level " << level);
    run_tool(encoder + " -cl " + level + " -qp 14 -i " + quoted(dir / "grid.ply") + " -o " +
                 quoted(dir / "grid.drc"),
             dir / "log.txt");
    const TriangleSoup read = io::read_surface(registry, dir / "grid.drc");
    REQUIRE(read.num_triangles() == grid.num_triangles());
    const VertexMatch match = match_vertices(grid, read);
    CHECK(match.max_position_error <= position_bound(grid, 14));
    CHECK(canonical_triangles(grid.triangles) == canonical_triangles(mapped_triangles(read, match)));
  }

  SECTION("a point cloud is not a mesh") {
    run_tool(encoder + " -point_cloud -i " + quoted(dir / "grid.ply") + " -o " + quoted(dir / "cloud.drc"),
             dir / "log.txt");
    CHECK_THROWS_WITH(io::read_surface(registry, dir / "cloud.drc"),
                      Catch::Contains("cloud.drc") && Catch::Contains("not a valid Draco mesh"));
  }
}
