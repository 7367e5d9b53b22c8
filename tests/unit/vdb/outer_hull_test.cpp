// The outer hull (libs/volume) on soups built here, checked with mr::check;
// and meshrepair taking it where rebuilding its input costs too much.

#include "mesh_generators.h"
#include "test_support.h"

#include <mr/check/distance.h>
#include <mr/check/surface_check.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/volume/outer_hull.h>
#include <mr/winding_number/winding_number.h>

#include <meshrepair.h>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <fstream>

namespace mr {
namespace {

TriangleSoup moved(TriangleSoup soup, const Vec3d& offset) {
  for (Vec3d& p : soup.positions) p += offset;
  return soup;
}

TriangleSoup turned_inward(TriangleSoup soup) {
  for (Triangle& t : soup.triangles) std::swap(t[1], t[2]);
  return soup;
}

constexpr double kVoxel = 0.025;

// The hull is closed, manifold, outward and free of self-intersections,
// within (wall radius + 1) voxels of the soup, and the soup within that of it.
check::SurfaceReport require_hull_of(const TriangleSoup& hull, const TriangleSoup& soup) {
  const check::SurfaceReport report = check::check_surface(hull);
  CAPTURE(check::watertight_failures(report));
  REQUIRE(report.watertight());
  const double reach = 2.0 * kVoxel;
  REQUIRE(check::one_sided_distance(hull, soup).max <= reach);
  return report;
}

volume::OuterHullOptions hull_options() {
  volume::OuterHullOptions options;
  options.voxel_size = kVoxel;
  return options;
}

}  // namespace

TEST_CASE("the outer hull of crossing cubes is one solid around their union", "[volume][vdb]") {
  TriangleSoup soup = test::cube_soup();
  soup.append(moved(test::cube_soup(), {0.5, 0.5, 0.5}));
  const TriangleSoup hull = volume::outer_hull(soup, hull_options());
  const check::SurfaceReport report = require_hull_of(hull, soup);
  REQUIRE(report.components == 1);
  // The union (2 - 1/8) grown by at most two voxels on each side.
  REQUIRE(report.volume > 2.0 - 0.125);
  REQUIRE(report.volume < (2.0 - 0.125) + 8.0 * 2.0 * kVoxel);
  // Only the outer faces bound it: the faces inside the union are far.
  REQUIRE(check::one_sided_distance(soup, hull).max > 0.2);
}

TEST_CASE("the outer hull's closing brings its surface back toward the soup", "[volume][vdb]") {
  TriangleSoup soup = test::cube_soup();
  soup.append(moved(test::cube_soup(), {0.5, 0.5, 0.5}));
  volume::OuterHullOptions options = hull_options();
  options.closing = 0.0;
  const TriangleSoup walls = volume::outer_hull(soup, options);
  options.closing = 0.5;
  const TriangleSoup closed = volume::outer_hull(soup, options);
  require_hull_of(walls, soup);
  require_hull_of(closed, soup);
  // One wall radius (a voxel) out, then half a voxel back.
  const double out = check::one_sided_distance(walls, soup).mean;
  const double back = check::one_sided_distance(closed, soup).mean;
  CAPTURE(out / kVoxel, back / kVoxel);
  REQUIRE(out > 0.8 * kVoxel);
  REQUIRE(back < 0.7 * kVoxel);
  options.closing = 0.6;  // more than wall radius less half a voxel
  REQUIRE_THROWS_AS(volume::outer_hull(soup, options), UsageError);
}

TEST_CASE("the outer hull keeps a hollow solid's cavity and fills an inward one", "[volume][vdb]") {
  const TriangleSoup cavity = turned_inward(test::cube_soup(0.3, 0.7));
  TriangleSoup hollow = test::cube_soup();
  hollow.append(cavity);
  const TriangleSoup hollow_hull = volume::outer_hull(hollow, hull_options());
  REQUIRE(require_hull_of(hollow_hull, hollow).components == 2);
  const Vec3d centre(0.5, 0.5, 0.5);
  REQUIRE(std::abs(winding_number_exact(hollow_hull, centre)) < 1e-6);
  REQUIRE(check::one_sided_distance(hollow, hollow_hull).max <= 2.0 * kVoxel);

  // A cube whose faces all point inward is still a solid (|w| = 1 inside).
  const TriangleSoup inward = turned_inward(test::cube_soup());
  const TriangleSoup inward_hull = volume::outer_hull(inward, hull_options());
  REQUIRE(require_hull_of(inward_hull, inward).components == 1);
  REQUIRE(std::abs(winding_number_exact(inward_hull, centre) - 1.0) < 1e-6);
}

TEST_CASE("the outer hull closes a crumpled sphere that crosses itself everywhere", "[volume][vdb]") {
  const TriangleSoup sphere = test::sphere(0.5, 4);
  const TriangleSoup crumpled_sphere = test::jittered(sphere, 0.05, 3);
  REQUIRE(check::check_surface(crumpled_sphere).self_intersecting_pairs > 100);
  const TriangleSoup hull = volume::outer_hull(crumpled_sphere, hull_options());
  const check::SurfaceReport report = require_hull_of(hull, crumpled_sphere);
  REQUIRE(report.components == 1);
  REQUIRE(report.volume > 4.0 / 3.0 * 3.14159 * 0.4 * 0.4 * 0.4);
}

TEST_CASE("the outer hull is the same on one thread and on two", "[volume][vdb][determinism]") {
  const TriangleSoup soup = test::jittered(test::sphere(0.5, 3), 0.03, 5);
  const auto hull_on = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return volume::outer_hull(soup, hull_options());
  };
  const TriangleSoup one = hull_on(1), two = hull_on(2);
  REQUIRE(one.positions == two.positions);
  REQUIRE(one.triangles == two.triangles);
}

TEST_CASE("the outer hull refuses a grid it cannot hold and bad options", "[volume][vdb]") {
  volume::OuterHullOptions options = hull_options();
  options.voxel_size = 1e-4;
  REQUIRE_THROWS_AS(volume::outer_hull(test::cube_soup(), options, 1'000'000), RunError);
  options.voxel_size = 0.0;
  REQUIRE_THROWS_AS(volume::outer_hull(test::cube_soup(), options), UsageError);
  options = hull_options();
  options.wall_radius = 0.5;
  REQUIRE_THROWS_AS(volume::outer_hull(test::cube_soup(), options), UsageError);
  REQUIRE(volume::outer_hull(TriangleSoup{}, hull_options()).triangles.empty());
}

TEST_CASE("meshrepair rebuilds the outer hull where rebuilding its input costs too much",
          "[volume][vdb][repair][e2e][slow]") {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("meshrepair_outer_hull");
  const TriangleSoup input = test::jittered(test::sphere(0.5, 3), 0.02, 7);
  const auto in = dir / "crumpled.stl", out = dir / "out.glb", stats = dir / "stats.json";
  io::write_surface(registry, input, in);
  const test::ToolRun run = test::run_tool(tools::meshrepair, {in.string(), out.string(), "--remesh",
                                                               "--max-tets", "1", "--stats", stats.string()});
  CAPTURE(run.err);
  REQUIRE(run.exit_code == 0);
  REQUIRE(run.err.find("outer hull") != std::string::npos);
  const TriangleSoup written = io::read_surface(registry, out);
  const check::SurfaceReport report = check::check_surface(written);
  CAPTURE(check::watertight_failures(report));
  REQUIRE(report.watertight());
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(stats));
  REQUIRE(j["path"] == "outer_hull");
  const double voxel = j["outer_hull"]["voxel_size"].get<double>();
  const double epsilon = j["epsilon_abs"].get<double>();
  REQUIRE(voxel > 0.0);
  // The hull within two voxels of the input, the output within epsilon of the hull.
  REQUIRE(check::one_sided_distance(written, input).max <= 2.0 * voxel + epsilon);
  REQUIRE(check::one_sided_distance(input, written).max <= 2.0 * voxel + epsilon);
}

}  // namespace mr
