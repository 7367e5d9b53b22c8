// STL, OBJ, OFF and PLY: round trips of the fixtures, attributes, and the
// format variants the readers accept (tristrips, endianness, OBJ index forms,
// OFF headers). Files are generated in code.

#include "file_checks.h"
#include "test_support.h"

#include <mr/core/errors.h>
#include <mr/io/mesh_io.h>
#include <mr/plugins/stl_obj_off_ply_formats.h>

#include <catch2/catch.hpp>

#include <bit>
#include <cstring>

using namespace mr;

namespace {

io::Registry plugin_registry() {
  io::Registry registry;
  plugins::register_stl_obj_off_ply_formats(registry);
  return registry;
}

TriangleSoup round_trip(const TriangleSoup& soup, const test::TempDir& dir, const std::string& file,
                        bool binary = true) {
  io::WriteOptions options;
  options.binary = binary;
  return test::round_trip(plugin_registry(), soup, dir / file, options);
}

TriangleSoup read_soup(const std::filesystem::path& path) {
  return io::read_surface(plugin_registry(), path);
}

// Same triangles, corner by corner, with positions equal (exactly, or after rounding to float).
void check_same_corners(const TriangleSoup& read, const TriangleSoup& original, bool float_precision) {
  REQUIRE(read.num_triangles() == original.num_triangles());
  for (std::size_t f = 0; f < original.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3d expected = original.positions[original.triangles[f][k]];
      const Vec3d got = read.positions[read.triangles[f][k]];
      if (float_precision)
        CHECK(got == expected.cast<float>().cast<double>());
      else
        CHECK(got == expected);
    }
}

void check_identical_geometry(const TriangleSoup& read, const TriangleSoup& original) {
  CHECK(read.positions == original.positions);
  CHECK(read.triangles == original.triangles);
}

// A soup with every attribute, with values that are not round in binary.
TriangleSoup attributed_cube() {
  TriangleSoup soup = test::cube_soup(-0.1, 0.7);
  for (std::size_t v = 0; v < soup.num_vertices(); ++v) {
    const float t = static_cast<float>(v);
    soup.normals.push_back(Vec3f(1.0f, t, 0.3f).normalized());
    soup.uvs.emplace_back(t / 7.0f, 1.0f - t / 9.0f);
    soup.colors.emplace_back(v / 7.0f, 0.5f, 1.0f - v / 7.0f, 1.0f);
  }
  for (std::size_t f = 0; f < soup.num_triangles(); ++f)
    soup.face_regions.push_back(static_cast<std::int32_t>(f / 4));
  soup.region_names = {"steel", "glass", "rubber"};
  return soup;
}

void check_normals_and_uvs(const TriangleSoup& read, const TriangleSoup& original) {
  REQUIRE(read.normals.size() == original.normals.size());
  REQUIRE(read.uvs.size() == original.uvs.size());
  for (std::size_t v = 0; v < original.normals.size(); ++v)
    CHECK((read.normals[v] - original.normals[v]).norm() < 1e-6f);
  for (std::size_t v = 0; v < original.uvs.size(); ++v) CHECK(read.uvs[v] == original.uvs[v]);
}

void check_colors(const TriangleSoup& read, const TriangleSoup& original, float tolerance) {
  REQUIRE(read.colors.size() == original.colors.size());
  for (std::size_t v = 0; v < original.colors.size(); ++v)
    CHECK((read.colors[v] - original.colors[v]).cwiseAbs().maxCoeff() <= tolerance);
}

void check_region_names_per_face(const TriangleSoup& read, const TriangleSoup& original) {
  REQUIRE(read.face_regions.size() == original.face_regions.size());
  for (std::size_t f = 0; f < original.face_regions.size(); ++f)
    CHECK(read.region_names.at(read.face_regions[f]) == original.region_names.at(original.face_regions[f]));
}

std::vector<char> binary_stl(const std::string& header_text,
                             const std::vector<std::array<float, 9>>& facets) {
  std::vector<char> bytes(84 + 50 * facets.size(), 0);
  std::memcpy(bytes.data(), header_text.data(), std::min<std::size_t>(80, header_text.size()));
  const auto count = static_cast<std::uint32_t>(facets.size());
  std::memcpy(bytes.data() + 80, &count, 4);
  for (std::size_t f = 0; f < facets.size(); ++f)
    std::memcpy(bytes.data() + 84 + 50 * f + 12, facets[f].data(), 36);
  return bytes;
}

template <class T>
void append_big_endian(std::vector<char>& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) bytes.push_back(raw[sizeof(T) - 1 - i]);
}

// Six vertices of a ladder in the z = 0 plane, for tristrip tests.
const char* const kLadderVertices = "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 2 0\n1 2 0\n";

void check_all_facing_up(const TriangleSoup& soup) {
  for (const Triangle& t : soup.triangles) {
    const Vec3d n =
        (soup.positions[t[1]] - soup.positions[t[0]]).cross(soup.positions[t[2]] - soup.positions[t[0]]);
    CHECK(n.z() > 0);
  }
}

}  // namespace

TEST_CASE("cube and non-manifold soup round-trip exactly through OBJ, OFF and PLY", "[openmesh]") {
  test::TempDir dir("om_exact");
  for (const std::string file : {"a.obj", "a.off", "a.ply", "ascii.ply"}) {
    INFO(file);
    const bool binary = file != "ascii.ply";
    for (const TriangleSoup& soup : {test::cube_soup(-0.1, 1.0 / 3.0), test::non_manifold_soup()}) {
      const TriangleSoup back = round_trip(soup, dir, file, binary);
      check_identical_geometry(back, soup);
      CHECK_FALSE(back.has_normals());
      CHECK_FALSE(back.has_face_regions());
    }
  }
}

TEST_CASE("isolated vertices survive OBJ, OFF and PLY", "[openmesh]") {
  test::TempDir dir("om_isolated");
  const TriangleSoup soup = test::non_manifold_soup();
  REQUIRE(soup.num_vertices() == 7);
  for (const std::string file : {"a.obj", "a.off", "a.ply"}) {
    INFO(file);
    const TriangleSoup back = round_trip(soup, dir, file);
    REQUIRE(back.num_vertices() == 7);
    CHECK(back.positions[6] == Vec3d(5, 5, 5));
  }
}

TEST_CASE("STL round trips keep every facet to float precision, binary and ASCII", "[openmesh][stl]") {
  test::TempDir dir("om_stl");
  for (bool binary : {true, false}) {
    INFO("binary " << binary);
    const TriangleSoup cube = test::cube_soup(-0.1, 1.0 / 3.0);
    const TriangleSoup back = round_trip(cube, dir, "cube.stl", binary);
    check_same_corners(back, cube, true);
    CHECK(back.num_vertices() == 8);  // 36 corners welded into the cube's 8 vertices
    CHECK(test::enclosed_volume(back) > 0);
  }
}

TEST_CASE("a non-manifold STL keeps duplicate, zero-area and repeated-index facets", "[openmesh][stl]") {
  test::TempDir dir("om_stl_nm");
  const TriangleSoup soup = test::non_manifold_soup();
  for (bool binary : {true, false}) {
    INFO("binary " << binary);
    const TriangleSoup back = round_trip(soup, dir, "nm.stl", binary);
    check_same_corners(back, soup, false);  // small integers and halves are exact in float
    CHECK(back.num_vertices() == 6);        // the isolated vertex cannot be stored in STL
    CHECK(back.triangles[3] == back.triangles[0]);
    CHECK(back.triangles[5][0] == back.triangles[5][1]);
  }
}

TEST_CASE("binary STL has computed facet normals and a header that does not start with solid",
          "[openmesh][stl]") {
  test::TempDir dir("om_stl_normals");
  TriangleSoup soup = test::cube_soup();
  soup.triangles.push_back({0, 1, 1});  // degenerate: zero normal
  io::write_surface(plugin_registry(), soup, dir / "n.stl");
  const std::vector<char> bytes = test::read_bytes(dir / "n.stl");
  REQUIRE(bytes.size() == 84 + 50 * 13);
  CHECK(std::string(bytes.data(), 5) != "solid");
  auto normal_of = [&](std::size_t facet) {
    float n[3];
    std::memcpy(n, bytes.data() + 84 + 50 * facet, sizeof(n));
    return Vec3f(n[0], n[1], n[2]);
  };
  CHECK(normal_of(0) == Vec3f(0, 0, -1));  // {0,2,1} on the z = 0 face, pointing out
  CHECK(normal_of(2) == Vec3f(0, 0, 1));
  CHECK(normal_of(12) == Vec3f::Zero());
}

TEST_CASE("a binary STL whose header starts with solid is read as binary", "[openmesh][stl]") {
  test::TempDir dir("om_stl_solid");
  const std::vector<std::array<float, 9>> facets = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}};
  test::write_bytes(dir / "solid.stl", binary_stl("solid fooled you", facets));
  const TriangleSoup soup = read_soup(dir / "solid.stl");
  CHECK(soup.num_triangles() == 2);
  CHECK(soup.num_vertices() == 4);
  CHECK(soup.positions[3] == Vec3d(1, 1, 0));
}

TEST_CASE("ASCII STL: keywords in any case, polygon loops fanned, solids become regions", "[openmesh][stl]") {
  const TriangleSoup soup = test::read_written(
      "two.stl",
      "solid first\n FACET NORMAL 0 0 1\n  OUTER LOOP\n   VERTEX 0 0 0\n   VERTEX 1 0 0\n"
      "   VERTEX 1 1 0\n   VERTEX 0 1 0\n  ENDLOOP\n ENDFACET\nENDSOLID first\n"
      "solid second\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 0 0 1e0\n"
      "endloop\nendfacet\nendsolid second\n",
      read_soup);
  REQUIRE(soup.num_triangles() == 3);
  CHECK(soup.num_vertices() == 5);
  CHECK(soup.face_regions == std::vector<std::int32_t>{0, 0, 1});
  CHECK(soup.region_names == std::vector<std::string>{"first", "second"});
}

TEST_CASE("attributes survive OBJ, OFF and PLY", "[openmesh]") {
  test::TempDir dir("om_attributes");
  const TriangleSoup soup = attributed_cube();
  SECTION("OBJ: normals, uvs, colours, usemtl regions") {
    const TriangleSoup back = round_trip(soup, dir, "a.obj");
    check_identical_geometry(back, soup);
    check_normals_and_uvs(back, soup);
    check_colors(back, soup, 0.0f);
    check_region_names_per_face(back, soup);
  }
  SECTION("OFF: normals, uvs, colours") {
    const TriangleSoup back = round_trip(soup, dir, "a.off");
    check_identical_geometry(back, soup);
    check_normals_and_uvs(back, soup);
    check_colors(back, soup, 0.0f);
  }
  for (bool binary : {true, false}) {
    SECTION(std::string("PLY: everything, colours as bytes, binary ") + (binary ? "yes" : "no")) {
      const TriangleSoup back = round_trip(soup, dir, "a.ply", binary);
      check_identical_geometry(back, soup);
      check_normals_and_uvs(back, soup);
      check_colors(back, soup, 0.5f / 255.0f + 1e-6f);
      CHECK(back.face_regions == soup.face_regions);
      CHECK(back.region_names == soup.region_names);
    }
  }
}

TEST_CASE("OBJ: polygons, negative indices, v/vt/vn forms, continuations, groups", "[openmesh][obj]") {
  const TriangleSoup soup =
      test::read_written("a.obj",
                         "# quad, then a triangle with relative indices\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                         "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                         "g plate\nf 1/1/1 2/2/1 \\\n 3/3/1 4/4/1\n"
                         "v 0 0 1\ng pin\nf -1 -5//-1 -4\nf 1//1 2//1 5//1\nl 1 2\n",
                         read_soup);
  REQUIRE(soup.num_vertices() == 5);
  REQUIRE(soup.triangles == std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {4, 0, 1}, {0, 1, 4}});
  CHECK(soup.region_names == std::vector<std::string>{"plate", "pin"});
  CHECK(soup.face_regions == std::vector<std::int32_t>{0, 0, 1, 1});
  REQUIRE(soup.has_uvs());
  CHECK(soup.uvs[2] == Vec2f(1, 0));  // v turned to glTF's convention: 1 - v
  CHECK(soup.uvs[4] == Vec2f(0, 0));  // no corner gave vertex 5 a uv
  REQUIRE(soup.has_normals());
  CHECK(soup.normals[0] == Vec3f(0, 0, 1));
  CHECK(soup.normals[4] == Vec3f(0, 0, 1));  // corners without a normal take the vertex's
}

TEST_CASE("OBJ: a seam splits a position into vertices, one per texture coordinate", "[openmesh][obj]") {
  const TriangleSoup soup = test::read_written("seam.obj",
                                               "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0\n"
                                               "f 1/1 2/2 3/3\nf 1/4 3/3 2/2\n",
                                               read_soup);
  REQUIRE(soup.num_vertices() == 4);
  CHECK(soup.positions[3] == soup.positions[0]);
  CHECK(soup.triangles == std::vector<Triangle>{{0, 1, 2}, {3, 2, 1}});
  CHECK(soup.uvs[0] == Vec2f(0, 1));
  CHECK(soup.uvs[3] == Vec2f(0.5f, 1));
}

TEST_CASE("OBJ: mtllib gives each usemtl region its colour, opacity and texture", "[openmesh][obj]") {
  test::TempDir dir("obj_mtl");
  const std::vector<char> png = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n', 'r', 'e', 's', 't'};
  test::write_bytes(dir / "wood.png", png);
  test::write_text(dir / "not_an_image.tga", "TGA");
  test::write_text(dir / "parts.mtl",
                   "# two materials and one the OBJ does not use\n"
                   "newmtl wood\nKd 0.5 0.25 0.125\nmap_Kd -s 1 1 1 -bm 0.5 wood.png\n"
                   "newmtl glass\nKd 0 0 1\nTr 0.75\nKe 0.1 0.2 0.3\nmap_Kd not_an_image.tga\n"
                   "newmtl unused\nKd 1 0 0\n");
  test::write_text(dir / "parts.obj",
                   "mtllib parts.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
                   "usemtl glass\nf 1/1 2/2 3/3\nusemtl wood\nf 1/1 2/2 4/3\nusemtl metal\nf 1 3 4\n");
  const TriangleSoup soup = read_soup(dir / "parts.obj");
  CHECK(soup.region_names == std::vector<std::string>{"glass", "wood", "metal"});
  REQUIRE(soup.materials.size() == 3);
  const Material& glass = soup.materials[0];
  CHECK(glass.name == "glass");
  CHECK(glass.base_color == std::array<float, 4>{0, 0, 1, 0.25f});
  CHECK(glass.alpha == Material::Alpha::blend);
  CHECK(glass.emissive == std::array<float, 3>{0.1f, 0.2f, 0.3f});
  CHECK(glass.base_color_image == -1);  // only PNG and JPEG are taken
  const Material& wood = soup.materials[1];
  CHECK(wood.base_color == std::array<float, 4>{0.5f, 0.25f, 0.125f, 1});
  CHECK(wood.metallic == 0.0f);
  REQUIRE(wood.base_color_image == 0);
  REQUIRE(soup.images.size() == 1);
  CHECK(soup.images[0].mime_type == "image/png");
  CHECK(soup.images[0].bytes == std::vector<std::uint8_t>(png.begin(), png.end()));
  CHECK(soup.materials[2].name == "metal");  // no entry in the library: a plain material
  CHECK(soup.materials[2].base_color_image == -1);

  SECTION("without its library the file still reads, without materials") {
    std::filesystem::remove(dir / "parts.mtl");
    const TriangleSoup bare = read_soup(dir / "parts.obj");
    CHECK(bare.materials.empty());
    CHECK(bare.region_names.size() == 3);
  }
  SECTION("a malformed number in the library names the library") {
    test::write_text(dir / "parts.mtl", "newmtl wood\nKd 0.5 oops 1\n");
    CHECK_THROWS_WITH(read_soup(dir / "parts.obj"), Catch::Contains("parts.mtl"));
  }
}

TEST_CASE("OFF: COFF colours, NOFF normals, counts glued to the keyword, comments", "[openmesh][off]") {
  test::TempDir dir("om_off");
  SECTION("counts glued to the keyword and face colours") {
    test::write_text(dir / "w.off",
                     "\t  OFF4 2 5 # counts\n0 0 0\n1 0 0\n# comment\n1 1 0\n0 1 0\n"
                     "4 0 1 2 3 1.0 0.0 0.0 0.75\n3 0 2 3\n");
    const TriangleSoup soup = read_soup(dir / "w.off");
    CHECK(soup.num_vertices() == 4);
    CHECK(soup.triangles == std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 2, 3}});
  }
  SECTION("COFF with byte colours") {
    test::write_text(dir / "c.off",
                     "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0\n0 1 0 0 0 255 51\n3 0 1 2\n");
    const TriangleSoup soup = read_soup(dir / "c.off");
    REQUIRE(soup.has_colors());
    CHECK(soup.colors[0] == Vec4f(1, 0, 0, 1));
    CHECK(soup.colors[1] == Vec4f(0, 1, 0, 1));
    CHECK(soup.colors[2].w() == Approx(0.2f));
  }
  SECTION("NOFF") {
    test::write_text(dir / "n.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n");
    const TriangleSoup soup = read_soup(dir / "n.off");
    REQUIRE(soup.has_normals());
    CHECK(soup.normals[2] == Vec3f(0, 0, 1));
  }
}

TEST_CASE("PLY tristrips become triangles with alternating orientation, ASCII and big endian",
          "[openmesh][ply]") {
  test::TempDir dir("om_tristrips");
  const std::vector<std::int32_t> strip = {0, 1, 2, 3, -1, 2, 3, 4, 5};
  SECTION("ASCII") {
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
        "property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n";
    text += kLadderVertices;
    text += std::to_string(strip.size());
    for (int i : strip) text += " " + std::to_string(i);
    test::write_text(dir / "s.ply", text + "\n");
    const TriangleSoup soup = read_soup(dir / "s.ply");
    REQUIRE(soup.num_triangles() == 4);
    CHECK(soup.triangles[0] == Triangle{0, 1, 2});
    CHECK(soup.triangles[1] == Triangle{2, 1, 3});
    check_all_facing_up(soup);
  }
  SECTION("binary big endian, double positions") {
    const std::string header =
        "ply\nformat binary_big_endian 1.0\nelement vertex 6\nproperty double x\n"
        "property double y\nproperty double z\nelement tristrips 1\n"
        "property list int int vertex_indices\nend_header\n";
    std::vector<char> bytes(header.begin(), header.end());
    const double xyz[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}, {1, 2, 0.1}};
    for (const auto& p : xyz)
      for (double c : p) append_big_endian(bytes, c);
    append_big_endian(bytes, static_cast<std::int32_t>(strip.size()));
    for (std::int32_t i : strip) append_big_endian(bytes, i);
    test::write_bytes(dir / "s.ply", bytes);
    const TriangleSoup soup = read_soup(dir / "s.ply");
    REQUIRE(soup.num_triangles() == 4);
    CHECK(soup.positions[5] == Vec3d(1, 2, 0.1));
    check_all_facing_up(soup);
  }
}

TEST_CASE("PLY: quads fanned, float colours, u/v names and unknown properties skipped", "[openmesh][ply]") {
  const TriangleSoup soup = test::read_written(
      "q.ply",
      "ply\nformat ascii 1.0\ncomment hello\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nproperty float confidence\nproperty float u\nproperty float v\n"
      "property float red\nproperty float green\nproperty float blue\n"
      "element face 1\nproperty list uchar int vertex_indices\nproperty uchar red\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
      "0 0 0 1 0 0 1 0 0\n1 0 0 1 1 0 0 1 0\n1 1 0 1 1 1 0 0 1\n0 1 0 1 0 1 0.5 0.5 0.5\n"
      "4 0 1 2 3 200\n0 1\n",
      read_soup);
  CHECK(soup.triangles == std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}});
  REQUIRE(soup.has_uvs());
  CHECK(soup.uvs[2] == Vec2f(1, 1));
  REQUIRE(soup.has_colors());
  CHECK(soup.colors[3] == Vec4f(0.5f, 0.5f, 0.5f, 1));
}

TEST_CASE("writers throw RunError when the stream fails", "[openmesh]") {
  const io::Registry registry = plugin_registry();
  const TriangleSoup soup = test::cube_soup();
  for (const std::string name : {"stl", "obj", "off", "ply"}) {
    INFO(name);
    const io::Format* format = registry.by_name(name);
    REQUIRE(format != nullptr);
    CHECK_THROWS_AS(format->write_surface(soup, "/nonexistent-dir/x." + name, {}), RunError);
    if (std::filesystem::exists("/dev/full"))
      CHECK_THROWS_AS(format->write_surface(soup, "/dev/full", {}), RunError);
  }
}

TEST_CASE("OBJ and PLY write region names as UTF-8, Latin-1 ones decoded", "[openmesh][utf8]") {
  test::TempDir dir("obj_ply_utf8_names");
  TriangleSoup cube = test::cube_soup();
  cube.face_regions = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2};
  cube.region_names = {"M\xE9tal",
                       "\xE9"
                       "k",
                       "d\xC3\xA9j\xC3\xA0 UTF-8"};
  const std::vector<std::string> utf8_names{"M\xC3\xA9tal",
                                            "\xC3\xA9"
                                            "k",
                                            "d\xC3\xA9j\xC3\xA0 UTF-8"};
  CHECK(round_trip(cube, dir, "names.obj").region_names == utf8_names);
  CHECK(round_trip(cube, dir, "names.ply").region_names == utf8_names);
  CHECK(round_trip(cube, dir, "names_ascii.ply", false).region_names == utf8_names);
}
