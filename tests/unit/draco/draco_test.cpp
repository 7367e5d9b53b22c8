#include "draco_test_support.h"

#include <mr/core/errors.h>
#include <mr/io/mesh_io.h>
#include <mr/plugins/draco_codec.h>
#include <mr/plugins/draco_formats.h>

#include <catch2/catch.hpp>

using namespace mr;
using namespace mr::draco_test;

namespace {

io::Registry drc_registry() {
  io::Registry registry;
  plugins::register_draco_formats(registry);
  return registry;
}

TriangleSoup roundtrip(const TriangleSoup& soup, const io::DracoOptions& options = {}) {
  const plugins::DracoEncoded encoded = plugins::encode_draco(soup, options);
  return plugins::decode_draco(std::string_view(encoded.bytes.data(), encoded.bytes.size()), "memory",
                               encoded.ids);
}

}  // namespace

TEST_CASE("draco round trip keeps a cube's attributes within quantization error", "[draco]") {
  const TriangleSoup cube = cube_with_attributes();
  const io::DracoOptions options;
  const plugins::DracoEncoded encoded = plugins::encode_draco(cube, options);
  CHECK(encoded.ids.position >= 0);
  CHECK(encoded.ids.normal >= 0);
  CHECK(encoded.ids.uv >= 0);
  CHECK(encoded.ids.color >= 0);
  const TriangleSoup decoded = plugins::decode_draco(
      std::string_view(encoded.bytes.data(), encoded.bytes.size()), "cube.drc", encoded.ids);
  REQUIRE(find_soup_inconsistency(decoded).empty());
  REQUIRE(decoded.num_vertices() == 8);
  CHECK(decoded.num_vertices() == encoded.num_points);
  CHECK(decoded.num_triangles() == encoded.num_faces);
  REQUIRE(decoded.has_normals());
  REQUIRE(decoded.has_uvs());
  REQUIRE(decoded.has_colors());

  const VertexMatch match = match_vertices(cube, decoded);
  CHECK(match.max_position_error <= position_bound(cube, options.position_bits));
  CHECK(canonical_triangles(cube.triangles) == canonical_triangles(mapped_triangles(decoded, match)));
  for (std::size_t v = 0; v < decoded.num_vertices(); ++v) {
    const Index o = match.original[v];
    CHECK((decoded.normals[v] - cube.normals[o]).norm() <= 4.0 / ((1 << options.normal_bits) - 1));
    CHECK((decoded.uvs[v] - cube.uvs[o]).cwiseAbs().maxCoeff() <= value_bound(1.0, options.uv_bits));
    CHECK((decoded.colors[v] - cube.colors[o]).cwiseAbs().maxCoeff() <= value_bound(1.0, options.color_bits));
  }
}

TEST_CASE("draco position error stays within the bound the quantization bits give", "[draco]") {
  const TriangleSoup grid = make_grid(30, 20, 0.37);
  for (int bits : {6, 8, 11, 16, 24}) {
    io::DracoOptions options;
    options.position_bits = bits;
    const TriangleSoup decoded = roundtrip(grid, options);
    const VertexMatch match = match_vertices(grid, decoded);
    INFO("bits " << bits << " error " << match.max_position_error << " bound " << position_bound(grid, bits));
    CHECK(match.max_position_error <= position_bound(grid, bits));
    CHECK(canonical_triangles(grid.triangles) == canonical_triangles(mapped_triangles(decoded, match)));
  }
}

TEST_CASE("draco keeps every triangle of a non-manifold soup, degenerate and duplicate ones too", "[draco]") {
  const TriangleSoup soup = test::non_manifold_soup();
  for (int speed : {0, 5, 10}) {
    io::DracoOptions options;
    options.speed = speed;
    const plugins::DracoEncoded encoded = plugins::encode_draco(soup, options);
    const TriangleSoup decoded = plugins::decode_draco(
        std::string_view(encoded.bytes.data(), encoded.bytes.size()), "soup.drc", encoded.ids);
    REQUIRE(decoded.num_triangles() == soup.num_triangles());
    CHECK(encoded.num_faces == soup.num_triangles());
    const VertexMatch match = match_vertices(soup, decoded);
    CHECK(match.max_position_error <= position_bound(soup, options.position_bits));
    CHECK(canonical_triangles(soup.triangles) == canonical_triangles(mapped_triangles(decoded, match)));
  }
  SECTION("without the repeated-index face (edgebreaker path) duplicates and non-manifold edges survive") {
    TriangleSoup no_repeat = soup;
    no_repeat.triangles.pop_back();
    const TriangleSoup decoded = roundtrip(no_repeat);
    REQUIRE(decoded.num_triangles() == no_repeat.num_triangles());
    const VertexMatch match = match_vertices(no_repeat, decoded);
    CHECK(canonical_triangles(no_repeat.triangles) == canonical_triangles(mapped_triangles(decoded, match)));
  }
}

TEST_CASE("draco .drc file keeps face regions", "[draco]") {
  const io::Registry registry = drc_registry();
  test::TempDir dir("draco_regions");
  SECTION("cube: regions meet at shared vertices, which stay shared") {
    TriangleSoup cube = cube_with_attributes();
    cube.face_regions = {0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 7};
    io::write_surface(registry, cube, dir / "cube.drc");
    const TriangleSoup read = io::read_surface(registry, dir / "cube.drc");
    REQUIRE(read.has_face_regions());
    CHECK(read.num_vertices() == 8);
    const VertexMatch match = match_vertices(cube, read);
    CHECK(canonical_region_triangles(cube.triangles, cube.face_regions) ==
          canonical_region_triangles(mapped_triangles(read, match), read.face_regions));
  }
  SECTION("non-manifold soup: sequential encoding keeps regions too") {
    TriangleSoup soup = test::non_manifold_soup();
    soup.face_regions = {5, 4, 3, 2, 1, 0};
    io::write_surface(registry, soup, dir / "soup.drc");
    const TriangleSoup read = io::read_surface(registry, dir / "soup.drc");
    REQUIRE(read.num_triangles() == soup.num_triangles());
    const VertexMatch match = match_vertices(soup, read);
    CHECK(canonical_region_triangles(soup.triangles, soup.face_regions) ==
          canonical_region_triangles(mapped_triangles(read, match), read.face_regions));
  }
  SECTION("the glTF codec entry points leave regions out") {
    TriangleSoup cube = test::cube_soup();
    cube.face_regions.assign(cube.num_triangles(), 3);
    const TriangleSoup decoded = roundtrip(cube);
    CHECK_FALSE(decoded.has_face_regions());
    CHECK(decoded.num_triangles() == 12);
  }
}

TEST_CASE("draco compresses a 10k-triangle grid far below 36 bytes a triangle", "[draco]") {
  const TriangleSoup grid = make_grid(100, 50, 0.0);
  REQUIRE(grid.num_triangles() == 10000);
  const plugins::DracoEncoded encoded = plugins::encode_draco(grid, {});
  INFO("bytes " << encoded.bytes.size());
  CHECK(encoded.bytes.size() < grid.num_triangles() * 36 / 10);
  CHECK(roundtrip(grid).num_triangles() == grid.num_triangles());
}

TEST_CASE("draco speed changes the bytes, never the mesh", "[draco]") {
  const TriangleSoup grid = make_grid(40, 30, 0.21);
  for (int speed = 0; speed <= 10; ++speed) {
    io::DracoOptions options;
    options.speed = speed;
    const TriangleSoup decoded = roundtrip(grid, options);
    INFO("speed " << speed);
    REQUIRE(decoded.num_triangles() == grid.num_triangles());
    CHECK(decoded.num_vertices() == grid.num_vertices());
    const VertexMatch match = match_vertices(grid, decoded);
    CHECK(match.max_position_error <= position_bound(grid, options.position_bits));
    CHECK(canonical_triangles(grid.triangles) == canonical_triangles(mapped_triangles(decoded, match)));
  }
}

TEST_CASE("draco attribute ids find attributes; a wrong id or bad options are errors", "[draco]") {
  const TriangleSoup cube = cube_with_attributes();
  const plugins::DracoEncoded encoded = plugins::encode_draco(cube, {});
  const std::string_view bytes(encoded.bytes.data(), encoded.bytes.size());
  const TriangleSoup by_type = plugins::decode_draco(bytes, "cube.drc");
  CHECK(by_type.has_normals());
  CHECK(by_type.has_colors());
  plugins::DracoAttributeIds wrong = encoded.ids;
  wrong.normal = 99;
  CHECK_THROWS_WITH(plugins::decode_draco(bytes, "cube.drc", wrong),
                    Catch::Contains("cube.drc") && Catch::Contains("unique id 99"));

  const plugins::DracoEncoded plain = plugins::encode_draco(test::cube_soup(), {});
  CHECK(plain.ids.normal == -1);
  CHECK(plain.ids.uv == -1);
  CHECK(plain.ids.color == -1);

  io::DracoOptions bad;
  bad.position_bits = 31;
  CHECK_THROWS_AS(plugins::encode_draco(cube, bad), RunError);
  TriangleSoup huge = test::cube_soup();
  huge.positions[0].x() = 1e300;
  CHECK_THROWS_AS(plugins::encode_draco(huge, {}), RunError);
}

TEST_CASE("draco garbage .drc makes format-convert exit 2 naming the file", "[draco]") {
  test::TempDir dir("draco_garbage");
  test::write_text(dir / "bad.drc", "DRACO this is not a mesh at all");
  const test::ToolRun run =
      test::run_format_convert({(dir / "bad.drc").string(), (dir / "out.drc").string()});
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Contains("bad.drc") && Catch::Contains("not a valid Draco mesh"));
  CHECK_FALSE(std::filesystem::exists(dir / "out.drc"));
}
