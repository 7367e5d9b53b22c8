// Round trips through the MSH (4.1, 2.2; ASCII, binary) and Medit writers
// and readers, and readers on hand-written files with what real files hold:
// sparse 64-bit node tags, parametric nodes, element types to skip,
// second-order tets, physical names, comments and unused Medit keywords.

#include "file_checks.h"
#include "test_support.h"

#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <sstream>

using namespace mr;

namespace mr::test::tet_io {

/// An n x n x n grid of cubes, each split into 6 positively oriented tets
/// (Kuhn subdivision), with spacing 1/7 so that coordinates are not short
/// decimals; tet labels vary in runs and include 0 and negative values, and
/// every 5th tet contributes a labelled triangle.
TetMesh kuhn_grid(int n) {
  TetMesh mesh;
  const int m = n + 1;
  auto vertex = [m](int i, int j, int k) { return static_cast<Index>(i + m * (j + m * k)); };
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) mesh.positions.emplace_back(0.001 / 3 + i / 7.0, j / 7.0, -k / 7.0);
  const TetMesh unit = cube_tets();
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int cube = i + n * (j + n * k);
        for (const Tet& t : unit.tets) {
          Tet tet;
          for (int c = 0; c < 4; ++c) {
            const Index corner = t[c];
            tet[c] = vertex(i + (corner & 1), j + ((corner >> 1) & 1), k + ((corner >> 2) & 1));
          }
          std::swap(tet[1], tet[2]);  // z grows downward here: mirrored, so flip back to positive
          mesh.tets.push_back(tet);
          mesh.tet_labels.push_back(cube % 5 - 1);
          if (mesh.tets.size() % 5 == 0) {
            mesh.faces.push_back({tet[0], tet[2], tet[1]});
            mesh.face_labels.push_back(static_cast<std::int32_t>(mesh.faces.size() % 3) + 1);
          }
        }
      }
  return mesh;
}

}  // namespace mr::test::tet_io

namespace {

struct Variant {
  const char* file;
  bool binary;
  const char* msh_version;
};

const Variant kVariants[] = {{"a.msh", false, "4.1"},
                             {"b.msh", true, "4.1"},
                             {"c.msh", false, "2.2"},
                             {"d.msh", true, "2.2"},
                             {"e.mesh", false, "4.1"}};

TetMesh round_trip(const TetMesh& mesh, const test::TempDir& dir, const Variant& variant) {
  io::WriteOptions options;
  options.binary = variant.binary;
  options.msh_version = variant.msh_version;
  return test::round_trip(io::make_default_registry(), mesh, dir / variant.file, options);
}

void check_same(const TetMesh& a, const TetMesh& b) {
  REQUIRE(a.positions.size() == b.positions.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) REQUIRE(a.positions[i] == b.positions[i]);
  CHECK(a.tets == b.tets);
  CHECK(a.tet_labels == b.tet_labels);
  CHECK(a.faces == b.faces);
  CHECK(a.face_labels == b.face_labels);
}

double orient(const TetMesh& mesh, const Tet& t) {
  const Vec3d& a = mesh.positions[t[0]];
  return (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).dot(mesh.positions[t[3]] - a);
}

TetMesh read_mesh(const std::filesystem::path& path) {
  return io::read_volume(io::make_default_registry(), path);
}

}  // namespace

TEST_CASE("the grid fixture is positively oriented and labelled", "[tet_io]") {
  const TetMesh grid = test::tet_io::kuhn_grid(4);
  CHECK(grid.tets.size() == 384);
  CHECK(grid.faces.size() == 76);
  for (const Tet& t : grid.tets) REQUIRE(orient(grid, t) > 0);
  CHECK(test::tet_volume(grid) == Approx(64.0 / 343.0));
}

TEST_CASE("cube tets round-trip exactly through every MSH variant and Medit", "[tet_io]") {
  test::TempDir dir("tet_cube");
  const TetMesh cube = test::cube_tets();
  for (const Variant& variant : kVariants) {
    INFO(variant.file);
    check_same(cube, round_trip(cube, dir, variant));
  }
}

TEST_CASE("a 4x4x4 Kuhn grid with faces and odd labels round-trips exactly", "[tet_io]") {
  test::TempDir dir("tet_grid");
  const TetMesh grid = test::tet_io::kuhn_grid(4);
  for (const Variant& variant : kVariants) {
    INFO(variant.file);
    check_same(grid, round_trip(grid, dir, variant));
  }
}

TEST_CASE("a mesh without labels reads back with one label everywhere", "[tet_io]") {
  test::TempDir dir("tet_nolabels");
  TetMesh cube = test::cube_tets();
  cube.tet_labels.clear();
  for (const Variant& variant : kVariants) {
    INFO(variant.file);
    const TetMesh back = round_trip(cube, dir, variant);
    CHECK(back.tets == cube.tets);
    const std::int32_t expected = std::string(variant.file).ends_with(".mesh") ? 0 : 1;
    CHECK(back.tet_labels == std::vector<std::int32_t>(6, expected));
  }
}

TEST_CASE("MSH 4.1 ASCII output has entities and full precision", "[tet_io]") {
  test::TempDir dir("tet_text");
  TetMesh cube = test::cube_tets();
  cube.positions[0] = Vec3d(0.1, 1.0 / 3.0, -2e-300);
  const io::Registry registry = io::make_default_registry();
  io::WriteOptions options;
  options.binary = false;
  io::write_volume(registry, cube, dir / "c.msh", options);
  const std::string text = test::read_text(dir / "c.msh");
  CHECK(text.starts_with("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 6\n"));
  CHECK(text.find("0.1 0.3333333333333333 -2e-300\n") != std::string::npos);
  CHECK(text.find("3 4 4 1\n") != std::string::npos);  // volume entity 4 holds one tet of type 4
  CHECK(read_mesh(dir / "c.msh").positions[0] == cube.positions[0]);
}

TEST_CASE("extreme doubles survive every text writer exactly", "[tet_io]") {
  test::TempDir dir("tet_extreme");
  TetMesh cube = test::cube_tets();
  cube.positions[1] = Vec3d(5e-324, 1.7976931348623157e308, 2.2250738585072014e-308 / 3);
  cube.positions[2] = Vec3d(-0.1 - 0.2, 1e23, 123456789.123456789);
  for (const Variant& variant : kVariants) {
    INFO(variant.file);
    check_same(cube, round_trip(cube, dir, variant));
  }
}

TEST_CASE("MSH 4.1 reader: sparse 64-bit tags, parametric nodes, skipped types, tet10", "[tet_io]") {
  const TetMesh mesh = test::read_written("s.msh",
                                          "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                                          "$PhysicalNames\n1\n3 9 \"solid\"\n$EndPhysicalNames\n"
                                          "$Entities\n1 0 0 2\n"
                                          "5 0 0 0 0\n"
                                          "1 0 0 0 1 1 1 1 9 0\n"
                                          "2 0 0 0 1 1 1 0 0\n"
                                          "$EndEntities\n"
                                          "$Nodes\n2 5 1 1000000000010\n"
                                          "0 5 0 1\n1000000000010\n0 0 0\n"
                                          "3 1 1 4\n7\n1000000000003\n3\n42\n"
                                          "1 0 0 0.1 0.2 0.3\n0 1 0 0 0 0\n0 0 1 0 0 0\n0.5 0.5 0.5 0 0 0\n"
                                          "$EndNodes\n"
                                          "$Comments\nanything $Nodes here\n$EndComments\n"
                                          "$Elements\n4 4 1 4\n"
                                          "0 5 15 1\n1 1000000000010\n"
                                          "1 1 1 1\n2 1000000000010 7\n"
                                          "3 1 4 1\n3 1000000000010 7 1000000000003 3\n"
                                          "3 2 11 1\n4 1000000000010 1000000000003 7 3 42 42 42 42 42 42\n"
                                          "$EndElements\n",
                                          read_mesh);
  REQUIRE(mesh.positions.size() == 5);
  CHECK(mesh.positions[1] == Vec3d(1, 0, 0));
  REQUIRE(mesh.tets.size() == 2);
  CHECK(mesh.tets[0] == Tet{0, 1, 2, 3});
  CHECK(mesh.tets[1] == Tet{0, 2, 1, 3});
  CHECK(mesh.tet_labels == std::vector<std::int32_t>{9, 2});  // physical tag, else entity tag
  CHECK(mesh.faces.empty());
  CHECK(orient(mesh, mesh.tets[1]) < 0);  // read as written, not flipped
}

TEST_CASE("MSH 2.2 reader: ASCII with skipped elements and physical 0", "[tet_io]") {
  const TetMesh mesh = test::read_written("s.msh",
                                          "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                                          "$Nodes\n4\n10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n$EndNodes\n"
                                          "$Elements\n5\n"
                                          "1 15 2 0 1 10\n"
                                          "2 1 2 0 1 10 20\n"
                                          "3 2 2 6 2 10 30 20\n"
                                          "4 4 2 0 8 10 20 30 40\n"
                                          "5 4 3 11 8 1 10 20 30 40\n"
                                          "$EndElements\n",
                                          read_mesh);
  CHECK(mesh.tets == std::vector<Tet>{{0, 1, 2, 3}, {0, 1, 2, 3}});
  CHECK(mesh.tet_labels == std::vector<std::int32_t>{8, 11});
  CHECK(mesh.faces == std::vector<Triangle>{{0, 2, 1}});
  CHECK(mesh.face_labels == std::vector<std::int32_t>{6});
}

namespace {

// Builds an MSH 2.2 binary file, optionally in the other byte order.
class Msh2Binary {
 public:
  explicit Msh2Binary(bool swap) : swap_(swap) {}
  void text(const std::string& s) { bytes_.insert(bytes_.end(), s.begin(), s.end()); }
  template <class T>
  void put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (swap_) std::reverse(raw, raw + sizeof(T));
    bytes_.insert(bytes_.end(), raw, raw + sizeof(T));
  }
  const std::vector<char>& bytes() const { return bytes_; }

 private:
  bool swap_;
  std::vector<char> bytes_;
};

std::vector<char> msh2_binary_file(bool swap) {
  Msh2Binary f(swap);
  f.text("$MeshFormat\n2.2 1 8\n");
  f.put<std::int32_t>(1);
  f.text("\n$EndMeshFormat\n$Nodes\n4\n");
  const double coords[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 4; ++i) {
    f.put<std::int32_t>(100 + i);
    for (double c : coords[i]) f.put(c);
  }
  f.text("\n$EndNodes\n$Elements\n3\n");
  for (std::int32_t v : {1, 1, 3, 7, 5, 0, 1, 100, 101}) f.put(v);  // a line with 3 tags
  for (std::int32_t v : {4, 2, 2}) f.put(v);                        // two tets with 2 tags
  for (std::int32_t v : {2, 4, 12, 100, 101, 102, 103, 3, 0, 13, 100, 102, 101, 103}) f.put(v);
  f.text("\n$EndElements\n");
  return f.bytes();
}

}  // namespace

TEST_CASE("MSH 2.2 binary reader skips element blocks and handles byte order", "[tet_io]") {
  test::TempDir dir("tet_msh22b");
  for (bool swap : {false, true}) {
    INFO("swapped: " << swap);
    test::write_bytes(dir / "b.msh", msh2_binary_file(swap));
    const TetMesh mesh = read_mesh(dir / "b.msh");
    CHECK(mesh.positions[3] == Vec3d(0, 0, 1));
    CHECK(mesh.tets == std::vector<Tet>{{0, 1, 2, 3}, {0, 2, 1, 3}});
    CHECK(mesh.tet_labels == std::vector<std::int32_t>{4, 13});
  }
}

TEST_CASE("Medit reader: comments, skipped keywords, 1-based indices", "[tet_io]") {
  const TetMesh mesh = test::read_written("m.mesh",
                                          "# written by hand\nMeshVersionFormatted 2\nDimension\n3\n"
                                          "Vertices # four of them\n4\n0 0 0 1\n1 0 0 1\n0 1 0 2\n0 0 1 2\n"
                                          "Edges\n1\n1 2 5\nCorners\n2\n1 2\nRequiredVertices 1 3\n"
                                          "Ridges\n1\n1\nTriangles\n1\n1 3 2 4\n"
                                          "Tetrahedra\n2\n1 2 3 4 7\n1 3 2 4 -3\nNormals\n1\n0 0 1\nEnd\n",
                                          read_mesh);
  CHECK(mesh.positions.size() == 4);
  CHECK(mesh.tets == std::vector<Tet>{{0, 1, 2, 3}, {0, 2, 1, 3}});
  CHECK(mesh.tet_labels == std::vector<std::int32_t>{7, -3});
  CHECK(mesh.faces == std::vector<Triangle>{{0, 2, 1}});
  CHECK(mesh.face_labels == std::vector<std::int32_t>{4});
}

TEST_CASE("VTU output declares points, tets and labels", "[tet_io]") {
  test::TempDir dir("tet_vtu");
  const io::Registry registry = io::make_default_registry();
  io::WriteOptions options;
  options.binary = false;
  io::write_volume(registry, test::cube_tets(), dir / "c.vtu", options);
  const std::string text = test::read_text(dir / "c.vtu");
  CHECK(text.find("NumberOfPoints=\"8\" NumberOfCells=\"6\"") != std::string::npos);
  CHECK(text.find("10\n10\n10\n10\n10\n10\n") != std::string::npos);
  CHECK(text.find("Name=\"label\"") != std::string::npos);
  CHECK_THROWS_AS(io::read_volume(registry, dir / "c.vtu"), UsageError);
}

TEST_CASE("format-convert turns a .msh volume into its boundary surface", "[tet_io]") {
  test::TempDir dir("tet_to_surface");
  const io::Registry registry = io::make_default_registry();
  io::write_volume(registry, test::cube_tets(), dir / "cube.msh");
  const test::ToolRun run =
      test::run_format_convert({(dir / "cube.msh").string(), (dir / "cube.obj").string()});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const TriangleSoup surface = io::read_surface(registry, dir / "cube.obj");
  CHECK(surface.triangles.size() == 12);
  CHECK(test::enclosed_volume(surface) == Approx(1.0));
  const test::ToolRun medit =
      test::run_format_convert({(dir / "cube.msh").string(), (dir / "cube.mesh").string()});
  REQUIRE(medit.exit_code == 0);
  check_same(test::cube_tets(), read_mesh(dir / "cube.mesh"));
}
