// Output precision: the coordinate grids formats store positions on, the
// repair's rounding onto them, and meshrepair's promise on the written file.

#include "mesh_generators.h"
#include "test_support.h"

#include <mr/check/surface_check.h>
#include <mr/core/coordinate_grid.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/repair/round_to_grid.h>

#include <extract_boundary.h>
#include <format_convert.h>
#include <hole_fill_tool.h>
#include <meshrepair.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

using namespace mr;

namespace {

Eigen::Matrix3d some_rotation() {
  return Eigen::AngleAxisd(0.7, Vec3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
}

// Two unit cubes side by side, `gap` apart along x, rotated (or not) and
// moved to `offset`: closed, manifold and apart in doubles; when `gap` is
// below the grid's step, rounding each coordinate on its own makes them meet.
TriangleSoup cubes_apart_by(double gap, const Vec3d& offset, bool rotate = true) {
  TriangleSoup a = test::cube_soup(0.0, 1.0);
  TriangleSoup b = test::cube_soup(0.0, 1.0);
  for (Vec3d& p : b.positions) p += Vec3d(1.0 + gap, 0.3, 0.2);
  a.append(b);
  const Eigen::Matrix3d rotation = rotate ? some_rotation() : Eigen::Matrix3d::Identity();
  for (Vec3d& p : a.positions) p = rotation * p + offset;
  return a;
}

TriangleSoup rounded_naively(TriangleSoup soup, const CoordinateGrid& grid) {
  for (Vec3d& p : soup.positions) p = grid.nearest(p);
  return soup;
}

bool all_on(const TriangleSoup& soup, const CoordinateGrid& grid) {
  for (const Vec3d& p : soup.positions)
    if (!grid.holds(p)) return false;
  return true;
}

}  // namespace

TEST_CASE("float32 grid: nearest float, steps are neighbouring floats", "[grid]") {
  const CoordinateGrid grid = CoordinateGrid::float32();
  REQUIRE(grid.nearest(0, 0.1) == double(0.1f));
  REQUIRE(grid.step(1, 1.0, 1) == double(std::nextafter(1.0f, 2.0f)));
  REQUIRE(grid.step(2, 1.0, -2) == double(std::nextafter(std::nextafter(1.0f, 0.0f), 0.0f)));
  REQUIRE(grid.holds(Vec3d(0.5, -3.0, 1e-3f)));
  REQUIRE_FALSE(grid.holds(Vec3d(0.1, 0.0, 0.0)));
  REQUIRE(CoordinateGrid::doubles().holds(Vec3d(0.1, 0.2, 0.3)));
}

TEST_CASE("quantized grid: values as Draco dequantizes them, covering the box with a margin", "[grid]") {
  const Vec3d lo(-1.0, 2.0, 0.5), hi(3.0, 2.5, 0.75);
  const CoordinateGrid grid = CoordinateGrid::quantized_over(lo, hi, 10);
  const auto& q = grid.quantization();
  REQUIRE(q.bits == 10);
  for (int axis = 0; axis < 3; ++axis) {
    REQUIRE(q.origin[axis] < lo[axis]);
    REQUIRE(double(q.origin[axis]) + q.range > hi[axis]);
  }
  const float delta = q.range / 1023.0f;
  for (int level : {0, 1, 17, 512, 1023}) {
    const double value = double(float(float(level) * delta) + q.origin[0]);
    REQUIRE(grid.nearest(0, value) == value);
    if (level < 1023)
      REQUIRE(grid.step(0, value, 1) == double(float(float(level + 1) * delta) + q.origin[0]));
  }
  REQUIRE(grid.nearest(0, 1e9) == double(float(float(1023) * delta) + q.origin[0]));  // clamped to the range
}

TEST_CASE("grid spacing over a box: float steps grow with the coordinates", "[grid]") {
  const Vec3d far(1e9, 1e9, 1e9);
  // Floats between 2^29 and 2^30 (1e9 lies there) are 2^(29 - 23) = 64 apart.
  CHECK(CoordinateGrid::float32().spacing_over(far, far + Vec3d::Ones()) == 64.0);
  CHECK(CoordinateGrid::float32().spacing_over(Vec3d::Zero(), Vec3d::Ones()) == std::ldexp(1.0, -23));
  CHECK(CoordinateGrid::doubles().spacing_over(Vec3d::Zero(), Vec3d::Ones()) == std::ldexp(1.0, -52));
  // However many levels Draco has, its decoder adds them to the origin in float.
  const CoordinateGrid draco = CoordinateGrid::quantized_over(far, far + Vec3d::Ones(), 30);
  CHECK(draco.spacing_over(far, far + Vec3d::Ones()) >= 64.0);
  const CoordinateGrid near = CoordinateGrid::quantized_over(Vec3d::Zero(), Vec3d::Ones(), 16);
  CHECK(near.spacing_over(Vec3d::Zero(), Vec3d::Ones()) < 1e-4);
}

TEST_CASE("rounding to float32 keeps two nearly touching cubes apart", "[grid][repair]") {
  const CoordinateGrid grid = CoordinateGrid::float32();
  const TriangleSoup input = cubes_apart_by(2e-9, Vec3d(0.123456789, -0.31415926, 0.27182818));
  REQUIRE(check::check_surface(input).watertight());
  // Each coordinate rounded on its own: the facing sides cross or merge.
  REQUIRE_FALSE(check::check_surface(rounded_naively(input, grid)).watertight());

  TriangleSoup rounded = input;
  const repair::GridRoundingStats stats = repair::round_to_grid(rounded, grid);
  REQUIRE(all_on(rounded, grid));
  const check::SurfaceReport r = check::check_surface(rounded);
  CAPTURE(check::watertight_failures(r));
  REQUIRE(r.watertight());
  REQUIRE(rounded.triangles == input.triangles);
  REQUIRE(stats.moved == 16);
  // The facing sides go back from the nearest points to be placed one at a
  // time; the far sides stay where the whole-surface step put them.
  CAPTURE(stats.sent_back);
  REQUIRE(stats.sent_back > 0);
  REQUIRE(stats.sent_back < stats.moved);
  REQUIRE(stats.nearest_refused > 0);
  REQUIRE(stats.max_move < 1e-6);
}

TEST_CASE("rounding to a coarse Draco grid keeps nearly touching cubes apart", "[grid][repair]") {
  // Axis-aligned: the facing sides round to one plane and overlap.
  const TriangleSoup input = cubes_apart_by(1e-7, Vec3d(0.5, 0.25, -0.125), false);
  Vec3d lo = input.positions[0], hi = lo;
  for (const Vec3d& p : input.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const CoordinateGrid grid = CoordinateGrid::quantized_over(lo, hi, 11);  // steps of about 1.5e-3
  REQUIRE_FALSE(check::check_surface(rounded_naively(input, grid)).watertight());
  TriangleSoup rounded = input;
  repair::round_to_grid(rounded, grid);
  REQUIRE(all_on(rounded, grid));
  const check::SurfaceReport r = check::check_surface(rounded);
  CAPTURE(check::watertight_failures(r));
  REQUIRE(r.watertight());
}

TEST_CASE("rounding refuses to place vertices it cannot keep apart", "[grid][repair]") {
  // Two tetrahedra facing each other 1e-3 apart, on steps of about 0.4: with no
  // search the facing sides meet, and no edge of a tetrahedron can be collapsed.
  TriangleSoup input;
  input.positions = {{0.1, 0, 0},   {0.1, 1, 0},   {0.1, 0, 1},   {-0.9, 0, 0},
                     {0.101, 0, 0}, {0.101, 1, 0}, {0.101, 0, 1}, {1.101, 0, 0}};
  input.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {4, 5, 6}, {4, 7, 5}, {4, 6, 7}, {5, 7, 6}};
  REQUIRE(check::check_surface(input).self_intersecting_pairs == 0);
  const CoordinateGrid grid = CoordinateGrid::quantized_over(Vec3d::Constant(-3.0), Vec3d::Constant(3.0), 5);
  REQUIRE(grid.nearest(input.positions[0]) == grid.nearest(input.positions[4]));
  TriangleSoup rounded = input;
  repair::GridRoundingOptions no_search;
  no_search.max_steps = 0;
  REQUIRE_THROWS_AS(repair::round_to_grid(rounded, grid, no_search), RunError);
}

TEST_CASE("rounding gives up after the positions it may try, and a finer grid takes over", "[grid][repair]") {
  // The two tetrahedra of the previous case, on 5 bits without a search.
  TriangleSoup input;
  input.positions = {{0.1, 0, 0},   {0.1, 1, 0},   {0.1, 0, 1},   {-0.9, 0, 0},
                     {0.101, 0, 0}, {0.101, 1, 0}, {0.101, 0, 1}, {1.101, 0, 0}};
  input.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {4, 5, 6}, {4, 7, 5}, {4, 6, 7}, {5, 7, 6}};
  const Vec3d lo = Vec3d::Constant(-3.0), hi = Vec3d::Constant(3.0);
  const CoordinateGrid coarse = CoordinateGrid::quantized_over(lo, hi, 5);
  repair::GridRoundingOptions no_search;
  no_search.max_steps = 0;
  repair::GridRoundingOptions bounded = no_search;
  bounded.max_tries = 5;  // fewer than the vertices
  TriangleSoup rounded = input;
  REQUIRE_THROWS_WITH(repair::round_to_grid(rounded, coarse, bounded),
                      Catch::Contains("gave up") && Catch::Contains("5 tried positions"));

  // Asked for a finer grid up front (to bound the search on the coarse
  // one), then rounded onto it: 16 bits keep 1e-3 apart.
  int asked = 0;
  const repair::FinerGrid finer = [&](const CoordinateGrid& refused) -> std::optional<CoordinateGrid> {
    ++asked;
    if (refused.quantization().bits >= 16) return std::nullopt;
    return CoordinateGrid::quantized_over(lo, hi, 16);
  };
  rounded = input;
  const repair::GridRounding result = repair::round_to_grid_or_finer(rounded, coarse, finer, no_search);
  REQUIRE(result.finer_grids == 1);
  REQUIRE(result.grid.quantization().bits == 16);
  REQUIRE(asked == 2);
  REQUIRE(all_on(rounded, result.grid));
  REQUIRE(result.stats.tries >= input.positions.size());
  REQUIRE(check::check_surface(rounded).self_intersecting_pairs == 0);
}

TEST_CASE("a vertex no grid point works for is collapsed onto a placed neighbour", "[grid][repair]") {
  // Vertex v 1e-9 from its neighbour u: both round to one float32 point, and
  // with no search around the nearest point v has nowhere to go.
  TriangleSoup input = test::sphere(1.0, 2);
  for (Vec3d& p : input.positions) p += Vec3d(10.0, 10.0, 10.0);  // float32 steps near 1e-6
  const Triangle first = input.triangles[0];
  const Index u = first[0], v = first[1];
  input.positions[v] = input.positions[u] + 1e-9 * (input.positions[v] - input.positions[u]).normalized();
  REQUIRE(check::check_surface(input).watertight());
  const CoordinateGrid grid = CoordinateGrid::float32();
  REQUIRE(grid.nearest(input.positions[u]) == grid.nearest(input.positions[v]));
  TriangleSoup rounded = input;
  repair::GridRoundingOptions no_search;
  no_search.max_steps = 0;
  const repair::GridRoundingStats stats = repair::round_to_grid(rounded, grid, no_search);
  REQUIRE(stats.collapsed == 1);
  REQUIRE(rounded.positions.size() == input.positions.size() - 1);
  REQUIRE(rounded.triangles.size() == input.triangles.size() - 2);
  REQUIRE(all_on(rounded, grid));
  const check::SurfaceReport r = check::check_surface(rounded);
  CAPTURE(check::watertight_failures(r));
  REQUIRE(r.watertight());
}

TEST_CASE("float32 about an origin: exact steps of a power of two, chosen where floats are coarse",
          "[grid]") {
  const CoordinateGrid grid = CoordinateGrid::float32_about(Vec3d(1e6, -2.5, 0.0), 0x1p-20);
  CHECK(grid.kind() == CoordinateGrid::Kind::float32_about);
  CHECK(grid.nearest(0, 1e6 + 0.3) == 1e6 + std::round(0.3 * 0x1p20) * 0x1p-20);
  CHECK(grid.step(1, -2.5, 3) == -2.5 + 3 * 0x1p-20);
  CHECK(grid.holds(Vec3d(1e6 - 0x1p-20, -2.5 + 5 * 0x1p-20, 7 * 0x1p-20)));
  CHECK_FALSE(grid.holds(Vec3d(1e6 + 0x1p-21, 0.0, 0.0)));
  CHECK(grid.nearest(2, 1e9) == (0x1p24 - 1) * 0x1p-20);  // 2^24 - 1 units at most
  CHECK_THROWS_AS(CoordinateGrid::float32_about(Vec3d(0.1, 0, 0), 0x1p-20), UsageError);
  CHECK_THROWS_AS(CoordinateGrid::float32_about(Vec3d::Zero(), 0.3), UsageError);

  // Near the origin floats are as fine: plain float32 (files as before).
  CHECK(CoordinateGrid::float32_over(Vec3d(-1, -1, -1), Vec3d(2, 1, 1)).kind() ==
        CoordinateGrid::Kind::float32);
  // A unit box 1e5 away: floats are 2^-7 apart there, floats about its
  // centre 2^-23 (its half-size is below 2^0).
  const CoordinateGrid far = CoordinateGrid::float32_over(Vec3d(1e5, 0, 0), Vec3d(1e5 + 1, 1, 1));
  REQUIRE(far.kind() == CoordinateGrid::Kind::float32_about);
  CHECK(far.origin() == Vec3d(1e5 + 0.5, 0.5, 0.5));
  CHECK(far.spacing_over(Vec3d(1e5, 0, 0), Vec3d(1e5 + 1, 1, 1)) == 0x1p-23);
  CHECK(CoordinateGrid::float32().spacing_over(Vec3d(1e5, 0, 0), Vec3d(1e5 + 1, 1, 1)) == 0x1p-7);
  // At 2e9, doubles are 2^-22 apart: the unit stays above them.
  const CoordinateGrid farther = CoordinateGrid::float32_over(Vec3d(2e9, 0, 0), Vec3d(2e9 + 1, 1, 1));
  REQUIRE(farther.kind() == CoordinateGrid::Kind::float32_about);
  CHECK(farther.spacing_over(Vec3d(2e9, 0, 0), Vec3d(2e9 + 1, 1, 1)) == 0x1p-20);
}

TEST_CASE("glTF stores positions far from the origin about a node translation, exactly", "[grid][io]") {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("grid_gltf_far");
  const TriangleSoup soup = cubes_apart_by(0.5, Vec3d(1e6, -3e5, 2e6));
  Vec3d lo = soup.positions[0], hi = lo;
  for (const Vec3d& p : soup.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  for (const char* name : {"far.glb", "far.gltf"}) {
    CAPTURE(name);
    io::WriteOptions options;
    const CoordinateGrid grid = io::surface_position_grid(registry, dir / name, options, lo, hi);
    REQUIRE(grid.kind() == CoordinateGrid::Kind::float32_about);
    CHECK(grid.spacing_over(lo, hi) <= 0x1p-21);
    const TriangleSoup on_grid = rounded_naively(soup, grid);
    for (const bool told : {true, false}) {  // as meshrepair writes it, and as a plain write
      CAPTURE(told);
      if (told) options.gltf_position_grid = grid;
      io::write_surface(registry, on_grid, dir / name, options);
      const TriangleSoup back = io::read_surface(registry, dir / name);
      REQUIRE(back.positions.size() == on_grid.positions.size());
      for (std::size_t i = 0; i < back.positions.size(); ++i)
        REQUIRE(back.positions[i] == on_grid.positions[i]);
    }
  }
}

TEST_CASE("writers store positions exactly on the grid they announce", "[grid][io]") {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("grid_writers");
  TriangleSoup soup = cubes_apart_by(0.5, Vec3d(10.1, -0.2, 3.3));
  Vec3d lo = soup.positions[0], hi = lo;
  for (const Vec3d& p : soup.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (const char* name :
       {"out.stl", "out.glb", "out.gltf", "out.drc", "draco.glb", "out.obj", "out.ply", "out.off"}) {
    SECTION(name) {
      io::WriteOptions options;
      options.draco.position_bits = 14;
      options.draco.compress_gltf = std::string(name) == "draco.glb";
      const CoordinateGrid grid = io::surface_position_grid(registry, dir / name, options, lo, hi);
      if (grid.kind() == CoordinateGrid::Kind::quantized) options.draco.position_grid = grid.quantization();
      const TriangleSoup on_grid = rounded_naively(soup, grid);
      io::write_surface(registry, on_grid, dir / name, options);
      const TriangleSoup back = io::read_surface(registry, dir / name);
      CAPTURE(grid.name());
      REQUIRE(back.positions.size() == on_grid.positions.size());
      // Readers may reorder vertices (Draco): compare the sets.
      auto sorted = [](std::vector<Vec3d> p) {
        std::sort(p.begin(), p.end(), [](const Vec3d& a, const Vec3d& b) {
          return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
        });
        return p;
      };
      const std::vector<Vec3d> read = sorted(back.positions), expected = sorted(on_grid.positions);
      for (std::size_t i = 0; i < read.size(); ++i) {
        CAPTURE(i, read[i].x(), read[i].y(), read[i].z(), expected[i].x(), expected[i].y(), expected[i].z());
        REQUIRE(read[i] == expected[i]);
      }
    }
  }
}

TEST_CASE("a Draco file gives back exactly the values its grid holds, however many bits", "[grid][io]") {
  // Draco's encoder quantizes in float: on fine grids it stores some of the
  // values its decoder makes at a neighbouring level.
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("draco_bits");
  const Vec3d lo(-0.3, 1.2, 5.0), hi(0.9, 1.7, 5.4);
  for (int bits : {16, 22, 26, 30}) {
    CAPTURE(bits);
    const CoordinateGrid grid = CoordinateGrid::quantized_over(lo, hi, bits);
    const auto& q = grid.quantization();
    const float delta = q.range / static_cast<float>((std::int64_t{1} << bits) - 1);
    std::mt19937 random(static_cast<unsigned>(bits));
    std::uniform_int_distribution<std::int64_t> level(0, (std::int64_t{1} << bits) - 1);
    TriangleSoup soup;  // disjoint triangles whose corners are decoder values
    std::set<std::array<double, 3>> held, not_held;
    for (Index v = 0; v < 600; ++v) {
      Vec3d p;
      for (int axis = 0; axis < 3; ++axis)
        p[axis] = double(float(float(level(random)) * delta) + q.origin[static_cast<std::size_t>(axis)]);
      soup.positions.push_back(p);
      (grid.holds(p) ? held : not_held).insert({p.x(), p.y(), p.z()});
      if (v % 3 == 2) soup.triangles.push_back({v - 2, v - 1, v});
    }
    io::WriteOptions options;
    options.draco.position_grid = q;
    options.draco.position_bits = bits;
    io::write_surface(registry, soup, dir / "out.drc", options);
    std::set<std::array<double, 3>> back;
    for (const Vec3d& p : io::read_surface(registry, dir / "out.drc").positions)
      back.insert({p.x(), p.y(), p.z()});
    for (const auto& p : held) REQUIRE(back.count(p) == 1);
    if (bits == 16) REQUIRE(not_held.empty());
    if (bits == 22 || bits == 26) {
      REQUIRE(!not_held.empty());
      for (const auto& p : not_held) REQUIRE(back.count(p) == 0);
    }
    // At 30 bits float arithmetic collapses 64 levels onto one value, and
    // the grid's nearest() misses some of them: it refuses those (safe).
    if (bits == 30) REQUIRE(held.size() > 9 * not_held.size());
  }
}

TEST_CASE("meshrepair's STL, GLB and Draco outputs stay watertight where float32 would merge two parts",
          "[grid][repair][e2e][slow]") {
  // Two cubes far from the origin, 0.01 epsilon apart: less than half a float32
  // step there, so a surface written as float32 without care merges them.
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("meshrepair_grid");
  TriangleSoup a = test::cube_soup(0.0, 1.0), b = test::cube_soup(0.0, 1.0);
  const double epsilon = 1e-3 * std::sqrt(6.0);
  for (Vec3d& p : b.positions) p += Vec3d(1.0 + 0.01 * epsilon, 0.0, 0.0);
  a.append(b);
  for (Vec3d& p : a.positions) p += Vec3d(1000.0, 0.0, 0.0);
  const auto input = dir / "near.obj";
  io::write_surface(registry, a, input);

  const auto in_doubles = dir / "out.obj";
  REQUIRE(test::run_tool(tools::meshrepair, {input.string(), in_doubles.string(), "-q"}).exit_code == 0);
  const TriangleSoup doubles = io::read_surface(registry, in_doubles);
  REQUIRE(check::check_surface(doubles).watertight());
  REQUIRE_FALSE(check::check_surface(rounded_naively(doubles, CoordinateGrid::float32())).watertight());

  for (const char* name : {"out.stl", "out.glb", "out.drc"}) {
    SECTION(name) {
      const auto output = dir / name, stats = dir / "stats.json";
      const test::ToolRun run = test::run_tool(
          tools::meshrepair, {input.string(), output.string(), "-q", "--stats", stats.string()});
      CAPTURE(run.err);
      REQUIRE(run.exit_code == 0);
      const check::SurfaceReport r = check::check_surface(io::read_surface(registry, output));
      CAPTURE(check::watertight_failures(r));
      REQUIRE(r.watertight());
      REQUIRE(r.components == 2);
      std::ifstream stats_file(stats);
      const nlohmann::json j = nlohmann::json::parse(stats_file);
      REQUIRE(j["written_file"]["watertight"] == true);
      REQUIRE(j["repair"]["rounded_vertices"].get<int>() > 0);
    }
  }
}

TEST_CASE("meshrepair refuses at once a format that cannot store the model within epsilon", "[grid][e2e]") {
  // A unit cube 1e9 from the origin: floats there are 64 apart, epsilon is
  // 0.0017. Rounding onto them merged every vertex, and the search for
  // places keeping the surface apart ran for minutes. GLB stores floats
  // about a node translation (2^-20 apart there) and holds it.
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("meshrepair_far");
  TriangleSoup cube = test::cube_soup(0.0, 1.0);
  for (Vec3d& p : cube.positions) p += Vec3d(1e9, -2e9, 5e8);
  cube.triangles.pop_back();  // a hole, so that there is something to repair
  const auto input = dir / "far.obj";
  io::write_surface(registry, cube, input);
  for (const char* name : {"out.stl", "out.drc"}) {
    SECTION(name) {
      const auto output = dir / name;
      const test::ToolRun run = test::run_tool(tools::meshrepair, {input.string(), output.string(), "-q"});
      CHECK(run.exit_code == 2);
      CHECK_THAT(run.err, Catch::Contains(output.string()) && Catch::Contains("apart where the model lies") &&
                              Catch::Contains("move the model nearer to the origin"));
      CHECK_FALSE(std::filesystem::exists(output));
    }
  }
  SECTION("hole-fill too") {
    const auto output = dir / "filled.stl";
    const test::ToolRun run = test::run_tool(tools::hole_fill, {input.string(), output.string(), "-q"});
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Catch::Contains("apart where the model lies"));
    CHECK_FALSE(std::filesystem::exists(output));
  }
  SECTION("format-convert, for a surface it would keep watertight") {
    TriangleSoup closed = test::cube_soup(0.0, 1.0);
    for (Vec3d& p : closed.positions) p += Vec3d(1e9, -2e9, 5e8);
    const auto closed_input = dir / "far_closed.obj", output = dir / "converted.stl";
    io::write_surface(registry, closed, closed_input);
    const test::ToolRun run =
        test::run_tool(tools::format_convert, {closed_input.string(), output.string(), "-q"});
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Catch::Contains("apart where the model lies"));
    CHECK_FALSE(std::filesystem::exists(output));
    const auto glb = dir / "converted.glb";
    CHECK(test::run_tool(tools::format_convert, {closed_input.string(), glb.string(), "-q"}).exit_code == 0);
    CHECK(io::read_surface(registry, glb).positions == closed.positions);
  }
  for (const char* name : {"out.obj", "out.glb", "filled.glb"}) {
    SECTION(std::string(name) + " holds it") {
      const auto output = dir / name;
      const bool fill = std::string(name) == "filled.glb";
      const test::ToolRun run = test::run_tool(fill ? tools::hole_fill : tools::meshrepair,
                                               {input.string(), output.string(), "-q"});
      CAPTURE(run.err);
      REQUIRE(run.exit_code == 0);
      const TriangleSoup back = io::read_surface(registry, output);
      CHECK(check::check_surface(back).watertight());
      for (const Vec3d& p : back.positions) CHECK((p - Vec3d(1e9, -2e9, 5e8)).cwiseAbs().maxCoeff() <= 1.01);
    }
  }
}

TEST_CASE("format-convert keeps a watertight surface watertight in float32, with the UVs of its seams",
          "[grid][e2e]") {
  // Two cubes 2e-9 apart: watertight in doubles, merged when rounded to
  // float32 naively. One corner is split into two vertices with different
  // UVs (a seam), as textured assets have.
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("format_convert_grid");
  TriangleSoup input = cubes_apart_by(2e-9, Vec3d(0.123456789, -0.31415926, 0.27182818));
  for (const Vec3d& p : input.positions) input.uvs.emplace_back(float(p.x()), float(p.y()));
  Triangle& first = input.triangles[0];
  input.positions.push_back(input.positions[first[0]]);
  input.uvs.emplace_back(0.5f, 0.5f);
  first[0] = Index(input.positions.size() - 1);
  REQUIRE(check::check_surface(input).watertight());
  REQUIRE_FALSE(check::check_surface(rounded_naively(input, CoordinateGrid::float32())).watertight());
  io::write_surface(registry, input, dir / "in.obj");
  for (const std::string name : {"out.glb", "out.stl"}) {
    CAPTURE(name);
    const test::ToolRun run =
        test::run_format_convert({(dir / "in.obj").string(), (dir / name).string(), "-q"});
    CAPTURE(run.err);
    REQUIRE(run.exit_code == 0);
    const TriangleSoup out = io::read_surface(registry, dir / name);
    const check::SurfaceReport r = check::check_surface(out);
    CAPTURE(check::watertight_failures(r));
    REQUIRE(r.watertight());
    REQUIRE(r.components == 2);
    if (name == "out.glb") {  // the seam's two vertices and their UVs stay
      REQUIRE(out.positions.size() == input.positions.size());
      REQUIRE(out.uvs.size() == input.uvs.size());
      CHECK(out.uvs.back() == Vec2f(0.5f, 0.5f));
    }
  }
}

TEST_CASE("extract-boundary writes a watertight boundary that stays watertight in float32", "[grid][e2e]") {
  // Two cubes of tets 2e-9 apart, rotated off the axes: their boundary is
  // watertight in doubles, and merges when rounded to float32 naively.
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("extract_boundary_grid");
  TetMesh mesh = test::cube_tets(), other = test::cube_tets();
  const auto offset = static_cast<Index>(mesh.positions.size());
  for (const Vec3d& p : other.positions) mesh.positions.push_back(p + Vec3d(1.0 + 2e-9, 0.3, 0.2));
  for (Tet t : other.tets) {
    for (Index& v : t) v += offset;
    mesh.tets.push_back(t);
  }
  mesh.tet_labels.assign(mesh.tets.size(), 1);
  const Eigen::Matrix3d rotation = some_rotation();
  for (Vec3d& p : mesh.positions) p = rotation * p + Vec3d(0.123456789, -0.31415926, 0.27182818);
  const auto input = dir / "two.msh";
  io::write_volume(registry, mesh, input);

  const auto obj = dir / "boundary.obj", stl = dir / "boundary.stl";
  REQUIRE(test::run_tool(tools::extract_boundary, {input.string(), obj.string(), "-q"}).exit_code == 0);
  const TriangleSoup doubles = io::read_surface(registry, obj);
  REQUIRE(check::check_surface(doubles).watertight());
  REQUIRE_FALSE(check::check_surface(rounded_naively(doubles, CoordinateGrid::float32())).watertight());

  const test::ToolRun run = test::run_tool(tools::extract_boundary, {input.string(), stl.string(), "-q"});
  CAPTURE(run.err);
  REQUIRE(run.exit_code == 0);
  const check::SurfaceReport r = check::check_surface(io::read_surface(registry, stl));
  CAPTURE(check::watertight_failures(r));
  REQUIRE(r.watertight());
  REQUIRE(r.components == 2);
}
