// glTF/GLB round trips, node transforms, primitive modes and external buffers.

#include "gltf_hand_built.h"
#include "test_support.h"

#include <mr/io/mesh_io.h>
#include <mr/plugins/gltf_formats.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <fstream>

using namespace mr;
using mr::test::gltf::HandBuilt;

namespace {

io::Registry gltf_registry() {
  io::Registry registry;
  plugins::register_gltf_formats(registry);
  return registry;
}

// The cube with per-vertex normals, uvs, colours and three named regions.
TriangleSoup attributed_cube() {
  TriangleSoup soup = test::cube_soup();
  for (std::size_t i = 0; i < soup.positions.size(); ++i) {
    const Vec3d p = soup.positions[i];
    soup.normals.push_back((p - Vec3d(0.5, 0.5, 0.5)).normalized().cast<float>());
    soup.uvs.emplace_back(static_cast<float>(p.x()), static_cast<float>(0.25 * p.y() + 0.5 * p.z()));
    soup.colors.emplace_back(static_cast<float>(i) / 8.0f, 0.5f, 1.0f - static_cast<float>(i) / 8.0f, 1.0f);
  }
  soup.face_regions = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2};
  soup.region_names = {"red", "green", "blue"};
  return soup;
}

void check_same_soup(const TriangleSoup& a, const TriangleSoup& b) {
  REQUIRE(a.num_vertices() == b.num_vertices());
  REQUIRE(a.num_triangles() == b.num_triangles());
  for (std::size_t i = 0; i < a.num_vertices(); ++i)
    CHECK((a.positions[i] - b.positions[i].cast<float>().cast<double>()).norm() == 0.0);
  CHECK(a.triangles == b.triangles);
  REQUIRE(a.has_normals() == b.has_normals());
  REQUIRE(a.has_uvs() == b.has_uvs());
  REQUIRE(a.has_colors() == b.has_colors());
  for (std::size_t i = 0; i < a.normals.size(); ++i) CHECK((a.normals[i] - b.normals[i]).norm() < 1e-6f);
  for (std::size_t i = 0; i < a.uvs.size(); ++i) CHECK(a.uvs[i] == b.uvs[i]);
  for (std::size_t i = 0; i < a.colors.size(); ++i) CHECK(a.colors[i] == b.colors[i]);
  CHECK(a.face_regions == b.face_regions);
  CHECK(a.region_names == b.region_names);
}

double min_x(const TriangleSoup& soup, std::size_t begin, std::size_t end) {
  double m = 1e300;
  for (std::size_t i = begin; i < end; ++i) m = std::min(m, soup.positions[i].x());
  return m;
}

// A tetrahedron with outward winding and outward per-vertex normals.
HandBuilt tetrahedron_model() {
  HandBuilt model;
  const std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::vector<float> n;
  for (int v = 0; v < 4; ++v) {
    const Vec3f d = Vec3f(p[3 * v], p[3 * v + 1], p[3 * v + 2]) - Vec3f(0.25f, 0.25f, 0.25f);
    const Vec3f u = d.normalized();
    n.insert(n.end(), {u.x(), u.y(), u.z()});
  }
  const int positions = model.add_floats(p, "VEC3", 3);
  const int normals = model.add_floats(n, "VEC3", 3);
  model.add_mesh({{"POSITION", positions}, {"NORMAL", normals}},
                 model.add_indices({0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}));
  return model;
}

void check_normals_outward(const TriangleSoup& soup, std::size_t begin, std::size_t end) {
  Vec3d centre = Vec3d::Zero();
  for (std::size_t i = begin; i < end; ++i) centre += soup.positions[i];
  centre /= static_cast<double>(end - begin);
  for (std::size_t i = begin; i < end; ++i) {
    CHECK(soup.normals[i].cast<double>().dot(soup.positions[i] - centre) > 0);
    CHECK(soup.normals[i].norm() == Approx(1.0f));
  }
}

// The JSON chunk of a GLB file.
nlohmann::json glb_json(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(bytes.size() > 20);
  std::uint32_t length;
  std::memcpy(&length, bytes.data() + 12, 4);
  REQUIRE(20 + length <= bytes.size());
  return nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + length);
}

}  // namespace

TEST_CASE("a cube with attributes and regions survives .glb and .gltf", "[gltf]") {
  const io::Registry registry = gltf_registry();
  test::TempDir dir("gltf_roundtrip");
  const TriangleSoup cube = attributed_cube();
  for (const char* name : {"cube.glb", "cube.gltf"}) {
    INFO(name);
    io::write_surface(registry, cube, dir / name);
    check_same_soup(io::read_surface(registry, dir / name), cube);
  }
  CHECK(dir.files() == std::vector<std::string>{"cube.glb", "cube.gltf"});  // one file each
}

TEST_CASE("face sources round-trip as the _SOURCE_FACE attribute, each face with its own vertices",
          "[gltf]") {
  const io::Registry registry = gltf_registry();
  test::TempDir dir("gltf_sources");
  TriangleSoup cube = attributed_cube();
  cube.face_sources = {7, 3, -1, 0, 11, 11, 5, 1, 2, 9, 4, 16777216};
  io::write_surface(registry, cube, dir / "cube.glb");
  const nlohmann::json json = glb_json(dir / "cube.glb");
  CHECK(json["meshes"][0]["primitives"][0]["attributes"].contains("_SOURCE_FACE"));
  const TriangleSoup back = io::read_surface(registry, dir / "cube.glb");
  REQUIRE(back.num_triangles() == cube.num_triangles());
  CHECK(back.num_vertices() == 3 * cube.num_triangles());
  CHECK(back.face_sources == cube.face_sources);  // regions in order already: the face order is kept
  for (std::size_t f = 0; f < cube.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      CHECK(back.positions[back.triangles[f][k]] == cube.positions[cube.triangles[f][k]]);
      CHECK(back.uvs[back.triangles[f][k]] == cube.uvs[cube.triangles[f][k]]);
    }

  cube.face_sources[0] = std::int64_t{1} << 25;  // past what a float holds exactly
  CHECK_THROWS_WITH(io::write_surface(registry, cube, dir / "big.glb"), Catch::Contains("_SOURCE_FACE"));
  CHECK(!std::filesystem::exists(dir / "big.glb"));
}

TEST_CASE("a soup without attributes or regions round-trips plainly", "[gltf]") {
  const io::Registry registry = gltf_registry();
  test::TempDir dir("gltf_plain");
  const TriangleSoup cube = test::cube_soup(-2.5, 3.125);
  io::write_surface(registry, cube, dir / "plain.glb");
  const TriangleSoup back = io::read_surface(registry, dir / "plain.glb");
  check_same_soup(back, cube);
  CHECK(test::enclosed_volume(back) == Approx(std::pow(5.625, 3)));
}

#if __has_include(<mr/plugins/draco_codec.h>)  // built with Draco (MR_WITH_DRACO)
TEST_CASE("GLB with Draco compression round-trips within quantization", "[gltf][draco]") {
  const io::Registry registry = gltf_registry();
  test::TempDir dir("gltf_draco");
  const TriangleSoup cube = attributed_cube();
  io::WriteOptions options;
  options.draco.compress_gltf = true;
  io::write_surface(registry, cube, dir / "cube.glb", options);
  const TriangleSoup back = io::read_surface(registry, dir / "cube.glb");
  REQUIRE(back.num_triangles() == cube.num_triangles());
  CHECK(back.has_normals());
  CHECK(back.has_uvs());
  CHECK(back.has_colors());
  CHECK(back.region_names == cube.region_names);
  for (int region = 0; region < 3; ++region)
    CHECK(std::count(back.face_regions.begin(), back.face_regions.end(), region) == 4);
  CHECK(test::enclosed_volume(back) == Approx(1.0).epsilon(1e-3));
  // The accessors must state the counts a Draco decoder returns.
  const nlohmann::json doc = glb_json(dir / "cube.glb");
  CHECK(doc["extensionsRequired"] == nlohmann::json::array({"KHR_draco_mesh_compression"}));
  std::size_t declared_vertices = 0;
  for (const auto& primitive : doc["meshes"][0]["primitives"]) {
    CHECK(primitive["extensions"].contains("KHR_draco_mesh_compression"));
    const auto& position = doc["accessors"][primitive["attributes"]["POSITION"].get<int>()];
    CHECK_FALSE(position.contains("bufferView"));
    CHECK(position.contains("min"));
    declared_vertices += position["count"].get<std::size_t>();
  }
  CHECK(declared_vertices == back.num_vertices());
  for (const Vec3d& p : back.positions) {
    double nearest = 1e300;
    for (const Vec3d& q : cube.positions) nearest = std::min(nearest, (p - q).norm());
    CHECK(nearest < 1e-3);
  }
}
#endif

TEST_CASE("node transforms apply through the hierarchy, mirrors keep faces outward", "[gltf]") {
  HandBuilt model = tetrahedron_model();
  const int translated = model.add_node({{"mesh", 0}, {"translation", {10.0, 0.0, 0.0}}});
  const int mirrored = model.add_node({{"mesh", 0}, {"scale", {-1.0, 1.0, 1.0}}});
  // A parent with a matrix (translate y by 5) and a child rotated 90 degrees about z.
  const int child = model.add_node({{"mesh", 0}, {"rotation", {0.0, 0.0, std::sqrt(0.5), std::sqrt(0.5)}}});
  const int parent = model.add_node(
      {{"matrix", {1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 5.0, 0.0, 1.0}},
       {"children", {child}}});
  model.set_scene({translated, mirrored, parent});
  test::TempDir dir("gltf_nodes");
  test::write_bytes(dir / "nodes.glb", model.glb());

  const TriangleSoup soup = io::read_surface(gltf_registry(), dir / "nodes.glb");
  REQUIRE(soup.num_vertices() == 12);
  REQUIRE(soup.num_triangles() == 12);
  CHECK(test::enclosed_volume(soup) == Approx(3.0 / 6.0));  // three outward unit tetrahedra
  CHECK(soup.positions[1].isApprox(Vec3d(11, 0, 0)));
  CHECK(soup.positions[5].isApprox(Vec3d(-1, 0, 0)));
  CHECK(min_x(soup, 4, 8) == Approx(-1.0));
  CHECK(soup.positions[9].isApprox(Vec3d(0, 6, 0), 1e-6));  // (1,0,0) rotated to (0,1,0), then up 5
  CHECK(soup.positions[10].isApprox(Vec3d(-1, 5, 0), 1e-6));
  for (std::size_t instance = 0; instance < 3; ++instance)
    check_normals_outward(soup, 4 * instance, 4 * instance + 4);
}

TEST_CASE("triangle strips and fans become consistently wound triangles", "[gltf]") {
  HandBuilt model;
  // Strip up a 2x3 grid of points in z=0: 4 triangles, all facing +z.
  const int strip_positions =
      model.add_floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0, 1, 2, 0}, "VEC3", 3);
  model.add_mesh({{"POSITION", strip_positions}}, -1, 5);
  // Fan around the origin: 3 triangles, all facing +z.
  const int fan_positions = model.add_floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0}, "VEC3", 3);
  model.add_mesh({{"POSITION", fan_positions}}, model.add_indices({0, 1, 2, 3, 4}), 6);
  // A line primitive, which holds no surface and is skipped.
  model.add_mesh({{"POSITION", fan_positions}}, -1, 1);
  model.set_scene(
      {model.add_node({{"mesh", 0}}), model.add_node({{"mesh", 1}}), model.add_node({{"mesh", 2}})});
  test::TempDir dir("gltf_modes");
  test::write_bytes(dir / "modes.glb", model.glb());

  const TriangleSoup soup = io::read_surface(gltf_registry(), dir / "modes.glb");
  REQUIRE(soup.num_triangles() == 7);
  for (const Triangle& t : soup.triangles) {
    const Vec3d n =
        (soup.positions[t[1]] - soup.positions[t[0]]).cross(soup.positions[t[2]] - soup.positions[t[0]]);
    CHECK(n.z() > 0);
    CHECK(n.z() == Approx(n.norm()));
  }
}

TEST_CASE(".gltf with an external .bin buffer and with a data URI", "[gltf]") {
  HandBuilt model = tetrahedron_model();
  model.set_scene({model.add_node({{"mesh", 0}})});
  test::TempDir dir("gltf_external");
  SECTION("external file beside the .gltf") {
    std::filesystem::create_directories(dir / "sub");
    test::write_text(dir / "sub" / "model.gltf", model.json_text("model%20data.bin"));
    test::write_text(dir / "sub" / "model data.bin", model.bin);
    const TriangleSoup soup = io::read_surface(gltf_registry(), dir / "sub" / "model.gltf");
    CHECK(soup.num_triangles() == 4);
    CHECK(test::enclosed_volume(soup) == Approx(1.0 / 6.0));
  }
  SECTION("base64 data URI") {
    // Write it once through our writer, which embeds the buffer, then read that.
    const io::Registry registry = gltf_registry();
    test::write_bytes(dir / "in.glb", model.glb());
    io::write_surface(registry, io::read_surface(registry, dir / "in.glb"), dir / "out.gltf");
    std::ifstream in(dir / "out.gltf");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(text.find("data:application/octet-stream;base64,") != std::string::npos);
    CHECK(io::read_surface(registry, dir / "out.gltf").num_triangles() == 4);
  }
}

TEST_CASE("primitives with and without attributes and materials combine consistently", "[gltf]") {
  HandBuilt model = tetrahedron_model();  // mesh 0: normals, no material
  const int positions = model.add_floats({5, 0, 0, 6, 0, 0, 5, 1, 0}, "VEC3", 3);
  const int colors = model.add_floats({1, 0, 0, 0, 1, 0, 0, 0, 1}, "VEC3", 3);
  model.add_mesh({{"POSITION", positions}, {"COLOR_0", colors}}, model.add_indices({0, 1, 2}));
  model.doc["meshes"][1]["primitives"][0]["material"] = 0;
  model.doc["materials"] = {{{"name", "paint"}}};
  model.set_scene({model.add_node({{"mesh", 0}}), model.add_node({{"mesh", 1}})});
  test::TempDir dir("gltf_mixed");
  test::write_bytes(dir / "mixed.glb", model.glb());

  const TriangleSoup soup = io::read_surface(gltf_registry(), dir / "mixed.glb");
  REQUIRE(soup.num_vertices() == 7);
  CHECK_FALSE(soup.has_normals());  // only some primitives had them: dropped
  REQUIRE(soup.has_colors());       // missing colours filled with white
  CHECK(soup.colors[0] == Vec4f(1, 1, 1, 1));
  CHECK(soup.colors[4] == Vec4f(1, 0, 0, 1));
  CHECK(soup.region_names == std::vector<std::string>{"paint", "default"});
  CHECK(soup.face_regions == std::vector<std::int32_t>{1, 1, 1, 1, 0});
}

TEST_CASE("an empty soup writes a valid empty scene", "[gltf]") {
  test::TempDir dir("gltf_empty");
  io::write_surface(gltf_registry(), TriangleSoup{}, dir / "empty.glb");
  CHECK(std::filesystem::file_size(dir / "empty.glb") > 20);
}

TEST_CASE("huge sparse region ids do not create millions of materials", "[gltf]") {
  const io::Registry registry = gltf_registry();
  test::TempDir dir("gltf_sparse_regions");
  TriangleSoup cube = test::cube_soup();
  cube.face_regions.assign(12, 1000000000);
  cube.face_regions[0] = 2;
  io::write_surface(registry, cube, dir / "regions.glb");
  CHECK(std::filesystem::file_size(dir / "regions.glb") < 4096);
  const TriangleSoup back = io::read_surface(registry, dir / "regions.glb");
  CHECK(back.region_names == std::vector<std::string>{"region_2", "region_1000000000"});
  REQUIRE(back.face_regions.size() == 12);
  CHECK(std::count(back.face_regions.begin(), back.face_regions.end(), 1) == 11);
}
