// hole-fill: every hole closed by a patch that meets the surface only along
// its loop, every input face kept, on holes built in code.
#include "file_checks.h"
#include "mesh_generators.h"
#include "meshrepair_run.h"
#include "test_support.h"

#include <mr/check/surface_check.h>
#include <mr/core/weld.h>
#include <mr/hole_fill/hole_fill.h>
#include <mr/hole_fill/redundant_faces.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <hole_fill_tool.h>
#include <meshrepair.h>

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>

using namespace mr;
using hole_fill::HoleOutcome;

namespace {

// `soup` without the faces whose centroid `cut` selects (vertices kept).
TriangleSoup without_faces(TriangleSoup soup, const std::function<bool(const Vec3d&)>& cut) {
  std::vector<Triangle> kept;
  for (const Triangle& t : soup.triangles) {
    const Vec3d c = (soup.positions[t[0]] + soup.positions[t[1]] + soup.positions[t[2]]) / 3.0;
    if (!cut(c)) kept.push_back(t);
  }
  soup.triangles = std::move(kept);
  return soup;
}

// The input's faces come first in the result, over the same positions.
void require_input_kept(const TriangleSoup& input, const hole_fill::HoleFillResult& result) {
  const TriangleSoup welded = weld_identical_vertices(input);
  REQUIRE(result.input_faces == welded.triangles.size());
  for (std::size_t f = 0; f < welded.triangles.size(); ++f) {
    REQUIRE(result.surface.triangles[f] == welded.triangles[f]);
    for (Index v : welded.triangles[f]) REQUIRE(result.surface.positions[v] == welded.positions[v]);
  }
}

void require_watertight(const TriangleSoup& surface) {
  const check::SurfaceReport report = check::check_surface(surface);
  INFO(check::watertight_failures(report));
  REQUIRE(report.watertight());
}

// The new vertex nearest to the z axis (the middle of a cap patch).
Vec3d middle_of_patch(const hole_fill::HoleFillResult& result, std::size_t input_vertices) {
  Vec3d best = Vec3d::Constant(std::nan(""));
  double best_r = INFINITY;
  for (std::size_t v = input_vertices; v < result.surface.positions.size(); ++v) {
    const Vec3d& p = result.surface.positions[v];
    if (p.head<2>().norm() < best_r) best_r = p.head<2>().norm(), best = p;
  }
  return best;
}

// The unit cube with a T-junction on edge 0-2: face (0, 2, 1) split at the
// edge's midpoint m (vertex 8) and the zero-area face (0, 2, m) closing the
// surface, so that face (0, 4, 2) across the edge meets it along 0-2.
TriangleSoup cube_with_zero_area_face() {
  TriangleSoup soup = test::cube_soup();
  soup.positions.emplace_back(0.0, 0.5, 0.0);
  soup.triangles[0] = {0, 8, 1};
  soup.triangles.push_back({8, 2, 1});
  soup.triangles.push_back({0, 2, 8});
  return soup;
}

// meshrepair on `input` written as dir/in.stl, output dir/`out`: it must
// succeed through the holes-only path. Its --stats.
nlohmann::json repaired_by_holes_only(const TriangleSoup& input, const test::TempDir& dir,
                                      const std::string& out) {
  nlohmann::json stats = test::meshrepair_stats(input, dir, "in.stl", out);
  REQUIRE(stats["path"] == "hole_fill");
  return stats;
}

}  // namespace

TEST_CASE("a zero-area face goes by splitting the face across its longest edge, nothing moved",
          "[hole_fill]") {
  const TriangleSoup input = cube_with_zero_area_face();
  const hole_fill::ZeroAreaRemoval removal = hole_fill::remove_zero_area_faces(input);
  REQUIRE(removal.dropped == 1);
  REQUIRE(removal.split == 1);
  REQUIRE(removal.left == 0);
  REQUIRE(removal.surface.positions == input.positions);
  require_watertight(removal.surface);
  // Every face but the zero-area one and face 8, (0, 4, 2), which is now
  // two faces meeting at m.
  std::multiset<test::PositionTriple> expected = test::position_triples(input);
  TriangleSoup gone;
  gone.positions = input.positions;
  gone.triangles = {input.triangles[8], input.triangles[13]};
  for (const test::PositionTriple& t : test::position_triples(gone)) expected.erase(expected.find(t));
  TriangleSoup halves;
  halves.positions = input.positions;
  halves.triangles = {{2, 8, 4}, {8, 0, 4}};
  for (const test::PositionTriple& t : test::position_triples(halves)) expected.insert(t);
  REQUIRE(test::position_triples(removal.surface) == expected);
}

TEST_CASE("copies of a face are dropped whichever way they face, the first kept", "[hole_fill]") {
  TriangleSoup soup = test::cube_soup();
  soup.triangles.push_back({2, 1, 0});  // face 0 turned
  soup.triangles.push_back({1, 2, 3});  // face 1 again
  soup.triangles.push_back({3, 1, 2});  // face 1 rotated
  REQUIRE(hole_fill::remove_repeated_faces(soup) == 3);
  REQUIRE(soup.triangles == test::cube_soup().triangles);
}

TEST_CASE("faces naming a vertex twice and zero-area mirror pairs are dropped", "[hole_fill]") {
  TriangleSoup input = test::cube_soup();
  input.triangles.push_back({3, 3, 5});
  // Two faces over one segment, facing each other: they enclose nothing.
  for (double x : {2.0, 3.0, 4.0}) input.positions.emplace_back(x, 0.0, 0.0);
  input.triangles.push_back({8, 10, 9});
  input.triangles.push_back({10, 8, 9});
  const hole_fill::ZeroAreaRemoval removal = hole_fill::remove_zero_area_faces(input);
  REQUIRE(removal.dropped == 3);
  REQUIRE(removal.split == 0);
  REQUIRE(removal.surface.triangles == test::cube_soup().triangles);
}

TEST_CASE("a sphere's missing cap is filled with a faired patch close to the sphere", "[hole_fill]") {
  const TriangleSoup input = without_faces(test::sphere(1.0, 5), [](const Vec3d& c) { return c.z() > 0.8; });
  const hole_fill::HoleFillResult result = hole_fill::fill_holes(input);
  REQUIRE(result.holes.size() == 1);
  REQUIRE(result.holes[0].outcome == HoleOutcome::filled);
  REQUIRE(result.holes[0].patch_vertices > 10);
  require_input_kept(input, result);
  require_watertight(result.surface);
  // A flat fill would be 0.2 below the sphere at the middle; the faired one is within 2% of the radius.
  const Vec3d middle = middle_of_patch(result, input.positions.size());
  INFO("middle of the patch " << middle.transpose());
  REQUIRE(std::abs(middle.norm() - 1.0) <= 0.02);
}

TEST_CASE("a cube's missing face is filled flat", "[hole_fill]") {
  const TriangleSoup input = without_faces(test::cube_soup(), [](const Vec3d& c) { return c.z() == 1.0; });
  REQUIRE(input.triangles.size() == 10);
  const hole_fill::HoleFillResult result = hole_fill::fill_holes(input);
  REQUIRE(result.filled() == 1);
  REQUIRE(result.holes[0].border_edges == 4);
  require_input_kept(input, result);
  require_watertight(result.surface);
  REQUIRE(std::abs(test::enclosed_volume(result.surface) - 1.0) < 1e-12);
  for (const Vec3d& p : result.surface.positions) REQUIRE(p.z() <= 1.0);
}

TEST_CASE("a saddle-shaped hole is filled without crossing itself", "[hole_fill]") {
  const TriangleSoup input = without_faces(test::sphere(1.0, 5), [](const Vec3d& c) {
    return c.z() > 0.55 + 0.25 * std::cos(2.0 * std::atan2(c.y(), c.x()));
  });
  const hole_fill::HoleFillResult result = hole_fill::fill_holes(input);
  REQUIRE(result.holes.size() == 1);
  REQUIRE(result.holes[0].outcome == HoleOutcome::filled);
  require_input_kept(input, result);
  require_watertight(result.surface);
}

TEST_CASE("a fill that would cut through a nearby part is retried until it does not", "[hole_fill]") {
  // A small closed sphere crosses the plane of the cap's loop: every flat fill meets it.
  TriangleSoup input = without_faces(test::sphere(1.0, 5), [](const Vec3d& c) { return c.z() > 0.8; });
  TriangleSoup blob = test::sphere(0.06, 2);
  for (Vec3d& p : blob.positions) p += Vec3d(0.0, 0.0, 0.79);
  input.append(blob);
  hole_fill::HoleFillOptions flat;
  flat.fairing = hole_fill::Fairing::none;
  flat.density = hole_fill::Density::coarse;
  const hole_fill::HoleFillResult result = hole_fill::fill_holes(input, flat);
  REQUIRE(result.holes.size() == 1);
  const hole_fill::HoleReport& hole = result.holes[0];
  INFO(hole.method << " after " << hole.attempts << " attempts");
  REQUIRE(hole.outcome == HoleOutcome::filled);
  REQUIRE(hole.attempts > 1);  // the flat patches were refused
  REQUIRE(hole.patch_vertices > 0);
  require_input_kept(input, result);
  require_watertight(result.surface);
}

TEST_CASE("a hole with an island is filled between the two loops, one part", "[hole_fill]") {
  // A band cut out of a sphere: the cap above it floats inside the hole.
  const TriangleSoup input =
      without_faces(test::sphere(1.0, 5), [](const Vec3d& c) { return c.z() > 0.6 && c.z() < 0.7; });
  REQUIRE(check::check_surface(input).components == 2);
  const hole_fill::HoleFillResult result = hole_fill::fill_holes(input);
  REQUIRE(result.holes.size() == 1);
  const hole_fill::HoleReport& hole = result.holes[0];
  INFO(hole.method);
  REQUIRE(hole.islands == 1);
  REQUIRE(hole.outcome == HoleOutcome::filled);
  require_input_kept(input, result);
  require_watertight(result.surface);
  // Filling each loop on its own would close the cap into a second part.
  REQUIRE(check::check_surface(result.surface).components == 1);
  // The band is put back close to the sphere.
  for (std::size_t v = input.positions.size(); v < result.surface.positions.size(); ++v)
    REQUIRE(std::abs(result.surface.positions[v].norm() - 1.0) < 0.02);
}

TEST_CASE("a band cut around a sphere is one hole whose far side is the island", "[hole_fill]") {
  // The part below the band reaches far from the band's plane: still an island of it.
  const TriangleSoup input =
      without_faces(test::sphere(1.0, 5), [](const Vec3d& c) { return c.z() > -0.35 && c.z() < -0.2; });
  REQUIRE(check::check_surface(input).components == 2);
  const hole_fill::HoleFillResult result = hole_fill::fill_holes(input);
  REQUIRE(result.holes.size() == 1);
  REQUIRE(result.holes[0].islands == 1);
  REQUIRE(result.holes[0].outcome == HoleOutcome::filled);
  require_input_kept(input, result);
  require_watertight(result.surface);
  REQUIRE(check::check_surface(result.surface).components == 1);
}

TEST_CASE("two holes sharing a border vertex are split into two loops and both filled", "[hole_fill]") {
  TriangleSoup sphere = test::sphere(1.0, 3);
  // Two faces around vertex 0 that share no edge: the border pinches at vertex 0.
  std::vector<std::size_t> around;
  for (std::size_t f = 0; f < sphere.triangles.size(); ++f)
    for (Index v : sphere.triangles[f])
      if (v == 0) around.push_back(f);
  REQUIRE(around.size() == 4);  // an octahedron's corner
  std::size_t second = 1;
  while (second < around.size()) {
    int shared = 0;
    for (Index a : sphere.triangles[around[0]])
      for (Index b : sphere.triangles[around[second]]) shared += a == b;
    if (shared == 1) break;
    ++second;
  }
  REQUIRE(second < around.size());
  TriangleSoup input = sphere;
  input.triangles.erase(input.triangles.begin() + std::ptrdiff_t(std::max(around[0], around[second])));
  input.triangles.erase(input.triangles.begin() + std::ptrdiff_t(std::min(around[0], around[second])));
  REQUIRE(check::check_surface(input).nonmanifold_vertices == 1);
  const hole_fill::HoleFillResult result = hole_fill::fill_holes(input);
  REQUIRE(result.holes.size() == 2);
  REQUIRE(result.filled() == 2);
  for (const hole_fill::HoleReport& h : result.holes) REQUIRE(h.border_edges == 3);
  require_input_kept(input, result);
  require_watertight(result.surface);
}

TEST_CASE("holes above the size limits are left open and counted", "[hole_fill]") {
  const TriangleSoup input = without_faces(test::cube_soup(), [](const Vec3d& c) { return c.z() == 1.0; });
  hole_fill::HoleFillOptions options;
  options.max_boundary = 3;
  REQUIRE(hole_fill::fill_holes(input, options).holes[0].outcome == HoleOutcome::too_long);
  options.max_boundary = 0;
  options.max_diameter = 1.0;  // the loop's box diagonal is sqrt(2)
  const hole_fill::HoleFillResult result = hole_fill::fill_holes(input, options);
  REQUIRE(result.holes[0].outcome == HoleOutcome::too_wide);
  REQUIRE(result.surface.triangles.size() == input.triangles.size());
}

TEST_CASE("told to stop at the first hole left open, a fill reports no hole after it", "[hole_fill]") {
  // The cube without its top and its bottom: two holes of four edges.
  const TriangleSoup input =
      without_faces(test::cube_soup(), [](const Vec3d& c) { return c.z() == 1.0 || c.z() == 0.0; });
  hole_fill::HoleFillOptions options;
  options.max_boundary = 3;
  REQUIRE(hole_fill::fill_holes(input, options).holes.size() == 2);
  options.stop_at_first_failure = true;
  const hole_fill::HoleFillResult stopped = hole_fill::fill_holes(input, options);
  REQUIRE(stopped.holes.size() == 1);
  REQUIRE(stopped.holes[0].outcome == HoleOutcome::too_long);
  // Holes that can be filled are all filled, as without the option.
  options.max_boundary = 0;
  const hole_fill::HoleFillResult filled = hole_fill::fill_holes(input, options);
  REQUIRE(filled.filled() == 2);
  require_watertight(filled.surface);
}

TEST_CASE("hole-fill writes the filled surface, checked as written, and its stats", "[hole_fill][e2e]") {
  const test::TempDir dir("hole_fill_tool");
  const io::Registry registry = io::make_default_registry();
  const TriangleSoup input = without_faces(test::sphere(1.0, 4), [](const Vec3d& c) { return c.z() > 0.7; });
  io::write_surface(registry, input, dir / "in.obj");
  const test::ToolRun run =
      test::run_tool(tools::hole_fill, {(dir / "in.obj").string(), (dir / "out.glb").string(), "--stats",
                                        (dir / "s.json").string(), "-j", "2"});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  REQUIRE(run.out.find("1 holes, 1 filled") != std::string::npos);
  const nlohmann::json stats = nlohmann::json::parse(std::ifstream(dir / "s.json"));
  REQUIRE(stats["holes_found"] == 1);
  REQUIRE(stats["holes_filled"] == 1);
  REQUIRE(stats["watertight"] == true);
  REQUIRE(stats["holes"][0]["patch_faces"].get<int>() > 0);
  require_watertight(io::read_surface(registry, dir / "out.glb"));

  for (const char* bad : {"--fair=3", "--density=fine", "--max-diameter=-1"}) {
    const std::string option(bad);
    const std::size_t eq = option.find('=');
    const test::ToolRun usage = test::run_tool(
        tools::hole_fill,
        {(dir / "in.obj").string(), (dir / "bad.glb").string(), option.substr(0, eq), option.substr(eq + 1)});
    REQUIRE(usage.exit_code == 2);
    REQUIRE(usage.err.find(option.substr(0, eq)) != std::string::npos);
    REQUIRE(!std::filesystem::exists(dir / "bad.glb"));
  }
}

TEST_CASE("meshrepair fills the holes of an input that lacks nothing else and keeps every face",
          "[hole_fill][e2e][slow]") {
  const test::TempDir dir("meshrepair_holes_only");
  const io::Registry registry = io::make_default_registry();
  const TriangleSoup input =
      without_faces(test::sphere(1.0, 4), [](const Vec3d& c) { return c.z() > 0.7 || c.x() > 0.8; });
  io::write_surface(registry, input, dir / "in.obj");
  const std::string in = (dir / "in.obj").string();

  const test::ToolRun run = test::run_tool(
      tools::meshrepair, {in, (dir / "out.obj").string(), "--stats", (dir / "s.json").string()});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const nlohmann::json stats = nlohmann::json::parse(std::ifstream(dir / "s.json"));
  REQUIRE(stats["path"] == "hole_fill");
  REQUIRE(stats["holes"]["filled"] == 2);
  const TriangleSoup out = io::read_surface(registry, dir / "out.obj");
  require_watertight(out);
  // OBJ keeps doubles: every input face is in the output, at the same positions.
  const TriangleSoup welded = weld_identical_vertices(input);
  for (std::size_t f = 0; f < welded.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i)
      REQUIRE(out.positions[out.triangles[f][i]] == welded.positions[welded.triangles[f][i]]);

  const test::ToolRun remesh =
      test::run_tool(tools::meshrepair,
                     {in, (dir / "remeshed.obj").string(), "--remesh", "--stats", (dir / "r.json").string()});
  REQUIRE(remesh.exit_code == 0);
  const nlohmann::json remeshed = nlohmann::json::parse(std::ifstream(dir / "r.json"));
  REQUIRE(remeshed["path"] == "tetrahedralize");
  REQUIRE(remeshed["hole_fill_declined"] == "--remesh");
  REQUIRE(remeshed["keep_input_abandoned"] == "");  // nothing to give up under --remesh
  // Both paths report their peak memory, in all and per input face.
  for (const nlohmann::json* figures : {&stats, &remeshed}) {
    const double peak_mb = (*figures)["memory"]["peak_mb"];
    CHECK(peak_mb > 1.0);
    CHECK((*figures)["memory"]["bytes_per_input_face"] ==
          Approx(peak_mb * 1048576.0 / input.triangles.size()));
  }
}

TEST_CASE("meshrepair takes zero-area faces out of an input that lacks nothing else, nothing moved",
          "[hole_fill][e2e]") {
  const test::TempDir dir("meshrepair_zero_area");
  const io::Registry registry = io::make_default_registry();
  const TriangleSoup input = cube_with_zero_area_face();
  const nlohmann::json stats = repaired_by_holes_only(input, dir, "out.glb");
  REQUIRE(stats["zero_area_faces"]["taken_out"] == 1);
  REQUIRE(stats["zero_area_faces"]["split_faces"] == 1);
  REQUIRE(stats["holes"]["kept_input_faces"] == 12);
  REQUIRE(stats["written_file"]["watertight"] == true);
  REQUIRE(test::position_triples(io::read_surface(registry, dir / "out.glb")) ==
          test::position_triples(hole_fill::remove_zero_area_faces(input).surface));
}

TEST_CASE("meshrepair drops repeated faces and turns flipped ones of an input that lacks nothing else",
          "[hole_fill][e2e]") {
  const test::TempDir dir("meshrepair_flipped");
  const io::Registry registry = io::make_default_registry();
  const TriangleSoup sphere = test::sphere(1.0, 3);
  TriangleSoup input = sphere;
  std::size_t flipped = 0;
  for (Triangle& t : input.triangles) {
    const Vec3d c = (input.positions[t[0]] + input.positions[t[1]] + input.positions[t[2]]) / 3.0;
    if (c.z() > 0.8) std::swap(t[1], t[2]), ++flipped;
  }
  REQUIRE(flipped > 3);
  REQUIRE(flipped < input.triangles.size() / 4);
  // Every tenth face doubled, every other copy turned the other way.
  std::size_t copies = 0;
  for (std::size_t f = 0; f < sphere.triangles.size(); f += 10, ++copies) {
    Triangle copy = input.triangles[f];
    if (copies % 2) std::swap(copy[0], copy[1]);
    input.triangles.push_back(copy);
  }
  const nlohmann::json stats = repaired_by_holes_only(input, dir, "out.obj");
  REQUIRE(stats["repeated_faces"] == copies);
  REQUIRE(stats["flipped_faces"] == flipped);
  REQUIRE(stats["written_file"]["watertight"] == true);
  REQUIRE(stats["provenance"]["kept_area_share"] == 1.0);
  // The sphere's faces as the STL input holds them (the copies come last).
  TriangleSoup expected = io::read_surface(registry, dir / "in.stl");
  expected.triangles.resize(sphere.triangles.size());
  REQUIRE(test::position_triples(io::read_surface(registry, dir / "out.obj")) ==
          test::position_triples(expected));
}

TEST_CASE("a watertight result is written on a finer Draco grid when the chosen one leaves no room",
          "[hole_fill][grid][e2e]") {
  // Two boxes 1e-6 apart and a flat tetrahedron in the gap: on the Draco grid chosen from
  // the size (steps near 1.5e-5) no grid level lies between the boxes, so the tetrahedron has
  // no place wherever its vertices are searched for, and it cannot be collapsed.
  TriangleSoup input = test::cube_soup();
  for (Vec3d& p : input.positions) p.z() *= 0.5;
  TriangleSoup upper = test::cube_soup();
  for (Vec3d& p : upper.positions) p.z() = 0.5 + 1e-6 + 0.5 * p.z();
  input.append(upper);
  TriangleSoup tet;
  tet.positions = {
      {0.4, 0.4, 0.5 + 2e-7}, {0.6, 0.4, 0.5 + 2e-7}, {0.5, 0.6, 0.5 + 2e-7}, {0.5, 0.5, 0.5 + 8e-7}};
  tet.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  input.append(tet);
  require_watertight(input);
  const test::TempDir dir("hole_fill_draco");
  const io::Registry registry = io::make_default_registry();
  io::write_surface(registry, input, dir / "in.obj");
  const test::ToolRun run =
      test::run_tool(tools::hole_fill, {(dir / "in.obj").string(), (dir / "out.drc").string()});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  require_watertight(io::read_surface(registry, dir / "out.drc"));
}

TEST_CASE("hole-fill writes the same bytes whatever the thread count", "[hole_fill][e2e]") {
  // A cap and scattered small holes: many patches made in parallel.
  TriangleSoup input = without_faces(test::sphere(1.0, 5), [](const Vec3d& c) {
    return c.z() > 0.8 || std::sin(40.0 * c.x()) * std::sin(40.0 * c.y()) > 0.995;
  });
  const test::TempDir dir("hole_fill_threads");
  const io::Registry registry = io::make_default_registry();
  io::write_surface(registry, input, dir / "in.obj");
  std::vector<std::string> outputs;
  for (const char* threads : {"1", "2", "4"}) {
    const std::string out = (dir / (std::string("out") + threads + ".obj")).string();
    const test::ToolRun run =
        test::run_tool(tools::hole_fill, {(dir / "in.obj").string(), out, "-j", threads, "-q"});
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    outputs.push_back(test::read_text(out));
  }
  REQUIRE(hole_fill::fill_holes(input).holes.size() > 10);
  REQUIRE(outputs[0] == outputs[1]);
  REQUIRE(outputs[0] == outputs[2]);
}
