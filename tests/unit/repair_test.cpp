// The repair stage of meshrepair on hand-built tet sets (independent of the
// tetrahedralization), verified with mr::check; and meshrepair end to end.

#include "mesh_generators.h"
#include "test_support.h"

#include <mr/check/distance.h>
#include <mr/check/surface_check.h>
#include <mr/core/boundary.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/repair/repair.h>
#include <mr/simplify/simplify.h>

#include <meshrepair.h>

#include <catch2/catch.hpp>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

using namespace mr;

namespace {

using Cell = std::array<int, 3>;

// Unit cells of the integer grid, each split into the 6 Kuhn tets along its
// main diagonal (the same in every cell, so the tets conform), positively
// oriented, corners shared between cells.
TetMesh grid_tets(const std::vector<Cell>& cells) {
  TetMesh mesh;
  std::map<Cell, Index> index;
  auto vertex = [&](int x, int y, int z) {
    const auto [it, added] = index.emplace(Cell{x, y, z}, Index(mesh.positions.size()));
    if (added) mesh.positions.emplace_back(x, y, z);
    return it->second;
  };
  const TetMesh unit = test::cube_tets();
  for (const Cell& c : cells)
    for (const Tet& t : unit.tets) {
      Tet tet;
      for (int k = 0; k < 4; ++k) {
        const Vec3d& p = unit.positions[t[k]];
        tet[k] = vertex(c[0] + int(p.x()), c[1] + int(p.y()), c[2] + int(p.z()));
      }
      mesh.tets.push_back(tet);
    }
  return mesh;
}

// A block of n^3 cells scaled into the unit cube.
TetMesh fine_cube_tets(int n) {
  std::vector<Cell> cells;
  for (int x = 0; x < n; ++x)
    for (int y = 0; y < n; ++y)
      for (int z = 0; z < n; ++z) cells.push_back({x, y, z});
  TetMesh mesh = grid_tets(cells);
  for (Vec3d& p : mesh.positions) p /= double(n);
  return mesh;
}

double epsilon_of(const TriangleSoup& input) { return 1e-3 * bounding_box_diagonal(input); }

repair::RepairResult repair_tets(const TetMesh& tets, const TriangleSoup& input, bool cleanup = true,
                                 std::span<const std::uint8_t> inside = {}) {
  repair::RepairOptions options;
  options.epsilon = epsilon_of(input);
  options.cleanup = cleanup;
  return repair::repair_surface_from_tets(tets, inside, input, options);
}

// Everything the issue asks of a repaired surface, measured independently.
void require_watertight(const TriangleSoup& surface, const TriangleSoup& input, double expected_volume,
                        double volume_tolerance) {
  const check::SurfaceReport r = check::check_surface(surface);
  CAPTURE(r.boundary_edges, r.nonmanifold_edges, r.nonmanifold_vertices, r.inconsistent_edges,
          r.degenerate_faces, r.self_intersecting_pairs, r.volume);
  REQUIRE(r.watertight());
  // No two vertices share a position (check_surface welds identical positions).
  REQUIRE(r.vertices == surface.positions.size());
  REQUIRE(r.volume == Approx(expected_volume).margin(volume_tolerance));
  const double epsilon = epsilon_of(input);
  const check::DistanceReport out_to_in = check::one_sided_distance(surface, input);
  const check::DistanceReport in_to_out = check::one_sided_distance(input, surface);
  CAPTURE(out_to_in.max, in_to_out.max, epsilon);
  REQUIRE(out_to_in.max <= epsilon);
  REQUIRE(in_to_out.max <= epsilon);
}

TriangleSoup translated(TriangleSoup soup, const Vec3d& offset) {
  for (Vec3d& p : soup.positions) p += offset;
  return soup;
}

TriangleSoup two_cubes(const Vec3d& offset) {
  TriangleSoup soup = test::cube_soup();
  soup.append(translated(test::cube_soup(), offset));
  return soup;
}

}  // namespace

TEST_CASE("a single cube of tets gives its 12 faces back", "[repair][slow]") {
  const TriangleSoup input = test::cube_soup();
  const repair::RepairResult result = repair_tets(test::cube_tets(), input);
  REQUIRE(result.manifold.nonmanifold_edges_found == 0);
  REQUIRE(result.manifold.nonmanifold_vertices_found == 0);
  REQUIRE(result.manifold.vertex_copies == 0);
  REQUIRE(result.surface.triangles.size() == 12);
  require_watertight(result.surface, input, 1.0, 1e-12);
  REQUIRE(result.stages.size() == 3);
  REQUIRE(result.stages[0].name == "manifold");
  REQUIRE(result.stages[2].name == "cleanup");
}

TEST_CASE("two cubes of tets sharing only an edge are pulled apart", "[repair][slow]") {
  const TetMesh tets = grid_tets({{0, 0, 0}, {1, 1, 0}});
  const TriangleSoup input = two_cubes({1, 1, 0});
  const check::SurfaceReport peeled = check::check_surface(extract_boundary(tets));
  REQUIRE(peeled.nonmanifold_edges == 1);  // the fixture really is broken
  for (bool cleanup : {false, true}) {
    const repair::RepairResult result = repair_tets(tets, input, cleanup);
    REQUIRE(result.manifold.nonmanifold_edges_found == 1);
    REQUIRE(result.manifold.vertex_copies == 2);  // both ends of the edge
    REQUIRE(result.manifold.removed_tets == 0);
    require_watertight(result.surface, input, 2.0, 1e-3);
    REQUIRE(check::check_surface(result.surface).components == 2);
  }
}

TEST_CASE("two cubes of tets sharing only a vertex are pulled apart", "[repair]") {
  const TetMesh tets = grid_tets({{0, 0, 0}, {1, 1, 1}});
  const TriangleSoup input = two_cubes({1, 1, 1});
  const repair::RepairResult result = repair_tets(tets, input);
  REQUIRE(result.manifold.nonmanifold_vertices_found == 1);
  REQUIRE(result.manifold.nonmanifold_edges_found == 0);
  REQUIRE(result.manifold.vertex_copies == 1);
  require_watertight(result.surface, input, 2.0, 1e-3);
}

TEST_CASE("a pinch whose tets are connected elsewhere is resolved", "[repair]") {
  // Two lower cells touch along an edge and are joined by an upper layer:
  // the top end of the edge has one connected star, so splitting alone
  // cannot resolve the edge.
  const TetMesh tets = grid_tets({{0, 0, 0}, {1, 1, 0}, {0, 0, 1}, {0, 1, 1}, {1, 1, 1}});
  const TriangleSoup input = extract_boundary(tets);
  const repair::RepairResult result = repair_tets(tets, input);
  REQUIRE(result.manifold.nonmanifold_edges_found == 1);
  const check::SurfaceReport r = check::check_surface(result.surface);
  CAPTURE(r.boundary_edges, r.nonmanifold_edges, r.nonmanifold_vertices, r.self_intersecting_pairs);
  REQUIRE(r.watertight());
  REQUIRE(r.vertices == result.surface.positions.size());
  REQUIRE(r.volume == Approx(5.0).margin(0.5));
}

TEST_CASE("a pinch between two solid layers is cut out inside the envelope", "[repair][slow]") {
  // A 2x2x3 block whose middle layer lacks two diagonal cells, with no
  // rejected tets on offer: the middle vertical edge is non-manifold, and
  // tets must go. The cells are 240 epsilon wide: removing a fan of them
  // exposes faces far from the input (4 outside the envelope without
  // collars). The collar of thin tets split around the edge keeps the
  // removal within a quarter epsilon of it.
  std::vector<Cell> cells;
  for (int z = 0; z < 3; ++z)
    for (int x = 0; x < 2; ++x)
      for (int y = 0; y < 2; ++y)
        if (z != 1 || (Cell{x, y, z} != Cell{1, 0, 1} && Cell{x, y, z} != Cell{0, 1, 1}))
          cells.push_back({x, y, z});
  const TetMesh tets = grid_tets(cells);
  const TriangleSoup input = extract_boundary(tets);
  REQUIRE(check::check_surface(input).nonmanifold_edges == 1);  // the fixture really is pinched
  const repair::RepairResult result = repair_tets(tets, input, false);
  REQUIRE(result.manifold.nonmanifold_edges_found == 1);
  REQUIRE(result.manifold.removed_tets > 0);
  REQUIRE(result.manifold.faces_outside_envelope == 0);
  const check::SurfaceReport r = check::check_surface(result.surface);
  CAPTURE(r.boundary_edges, r.nonmanifold_edges, r.nonmanifold_vertices, r.self_intersecting_pairs);
  REQUIRE(r.watertight());
  REQUIRE(r.vertices == result.surface.positions.size());
  const double epsilon = epsilon_of(input);
  REQUIRE(r.volume == Approx(10.0).margin(epsilon));
  REQUIRE(check::one_sided_distance(result.surface, input).max <= epsilon);
}

TEST_CASE("random tet subsets of a block become watertight surfaces", "[repair]") {
  const TetMesh block = fine_cube_tets(3);
  for (unsigned seed = 1; seed <= 6; ++seed) {
    CAPTURE(seed);
    std::mt19937 random(seed);
    TetMesh kept;
    kept.positions = block.positions;
    for (const Tet& t : block.tets)
      if (random() % 2) kept.tets.push_back(t);
    const TriangleSoup input = extract_boundary(kept);
    const repair::RepairResult result = repair_tets(kept, input);
    REQUIRE(result.manifold.nonmanifold_edges_found + result.manifold.nonmanifold_vertices_found > 0);
    const check::SurfaceReport r = check::check_surface(result.surface);
    CAPTURE(r.boundary_edges, r.nonmanifold_edges, r.nonmanifold_vertices, r.inconsistent_edges,
            r.degenerate_faces, r.self_intersecting_pairs, result.manifold.removed_tets,
            result.manifold.vertex_copies);
    REQUIRE(r.watertight());
    REQUIRE(r.vertices == result.surface.positions.size());
    REQUIRE(r.volume <= test::tet_volume(kept) + 1e-9);
  }
}

namespace {

// Each tet of `block` flagged inside with probability 1/2, and the flagged tets.
std::pair<std::vector<std::uint8_t>, TetMesh> random_half(const TetMesh& block, unsigned seed) {
  std::mt19937 random(seed);
  std::vector<std::uint8_t> inside(block.tets.size());
  TetMesh kept;
  kept.positions = block.positions;
  for (std::size_t t = 0; t < block.tets.size(); ++t) {
    inside[t] = random() % 2;
    if (inside[t]) kept.tets.push_back(block.tets[t]);
  }
  return {std::move(inside), std::move(kept)};
}

}  // namespace

TEST_CASE("random tet subsets with the rest of the block on offer become watertight surfaces", "[repair]") {
  // The manifold fix may now add rejected tets as well as remove kept ones,
  // and splits lock rejected tets out: every mix must still end manifold.
  const TetMesh block = fine_cube_tets(3);
  for (unsigned seed = 1; seed <= 6; ++seed) {
    CAPTURE(seed);
    const auto [inside, kept] = random_half(block, seed);
    const TriangleSoup input = extract_boundary(kept);
    const repair::RepairResult result = repair_tets(block, input, true, inside);
    const check::SurfaceReport r = check::check_surface(result.surface);
    CAPTURE(r.boundary_edges, r.nonmanifold_edges, r.nonmanifold_vertices, r.self_intersecting_pairs,
            result.manifold.removed_tets, result.manifold.added_tets, result.manifold.vertex_copies);
    REQUIRE(r.watertight());
    REQUIRE(r.vertices == result.surface.positions.size());
    REQUIRE(r.volume <= test::tet_volume(block) + 1e-9);
  }
}

TEST_CASE("when its rounds run out, the manifold fix falls back to filling the stars of defects",
          "[repair]") {
  // One round cannot resolve these random subsets; the fallback starts
  // again from the flags and only adds tets, so it ends manifold with at
  // least the volume that was kept.
  const TetMesh block = fine_cube_tets(3);
  int fell_back = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    CAPTURE(seed);
    const auto [inside, kept] = random_half(block, seed);
    TetMesh mesh = block;
    repair::ManifoldFixOptions options;
    options.max_move = 1e-3;
    options.max_rounds = 1;
    const repair::ManifoldFixStats stats = repair::make_boundary_manifold(mesh, inside, nullptr, options);
    const check::SurfaceReport r = check::check_surface(extract_boundary(mesh));
    CAPTURE(stats.fell_back, stats.fallback_steps, stats.fallback_added_tets, check::watertight_failures(r));
    REQUIRE(r.watertight());
    if (stats.fell_back) {
      ++fell_back;
      REQUIRE(stats.fallback_added_tets > 0);
      REQUIRE(mesh.tets.size() == kept.tets.size() + stats.fallback_added_tets);
      REQUIRE(test::tet_volume(mesh) >= test::tet_volume(kept) - 1e-12);
    }
  }
  REQUIRE(fell_back > 0);
}

TEST_CASE("a pinch in a thin layer is closed by adding rejected tets", "[repair][slow]") {
  // A 2x2x3 block whose thin middle layer lacks two diagonal cells: the
  // middle vertical edge is non-manifold, and both its ends have connected
  // stars, so no split helps. Removing the kept tets of one side would
  // expose faces as far from the input as the cells are wide; adding the
  // rejected tets of the thin layer around the edge keeps the surface
  // within the layer's thickness of the input.
  constexpr double kThin = 1e-4;
  std::vector<Cell> cells;
  for (int z = 0; z < 3; ++z)
    for (int x = 0; x < 2; ++x)
      for (int y = 0; y < 2; ++y) cells.push_back({x, y, z});
  TetMesh block = grid_tets(cells);
  for (Vec3d& p : block.positions) p.z() = p.z() <= 1 ? p.z() : p.z() - 1 + kThin;
  std::vector<std::uint8_t> inside(block.tets.size());
  TetMesh kept;
  kept.positions = block.positions;
  for (std::size_t t = 0; t < block.tets.size(); ++t) {
    const Cell& cell = cells[t / 6];
    inside[t] = cell != Cell{1, 0, 1} && cell != Cell{0, 1, 1};
    if (inside[t]) kept.tets.push_back(block.tets[t]);
  }
  const TriangleSoup input = extract_boundary(kept);
  REQUIRE(check::check_surface(input).nonmanifold_edges == 1);  // the fixture really is pinched

  const repair::RepairResult result = repair_tets(block, input, false, inside);
  REQUIRE(result.manifold.nonmanifold_edges_found == 1);
  REQUIRE(result.manifold.vertex_copies == 0);
  REQUIRE(result.manifold.removed_tets == 0);
  REQUIRE(result.manifold.added_tets > 0);
  REQUIRE(result.manifold.faces_outside_envelope == 0);
  const check::SurfaceReport r = check::check_surface(result.surface);
  REQUIRE(r.watertight());
  REQUIRE(r.vertices == result.surface.positions.size());
  REQUIRE(r.volume == Approx(test::tet_volume(kept)).margin(2 * kThin));
  const double out_to_in = check::one_sided_distance(result.surface, input).max;
  CAPTURE(out_to_in, check::one_sided_distance(input, result.surface).max);
  REQUIRE(out_to_in <= 2 * kThin);
}

TEST_CASE("the clean-up makes a dense peeled surface coarse inside the envelope", "[repair][slow]") {
  const TetMesh tets = fine_cube_tets(4);
  const TriangleSoup input = test::cube_soup();
  const repair::RepairResult dense = repair_tets(tets, input, false);
  const repair::RepairResult clean = repair_tets(tets, input, true);
  REQUIRE(dense.surface.triangles.size() == 6 * 16 * 2);
  REQUIRE(clean.peeled_faces == dense.surface.triangles.size());
  REQUIRE(clean.collapses > 0);
  REQUIRE(clean.surface.triangles.size() <= dense.surface.triangles.size() / 4);
  require_watertight(clean.surface, input, 1.0, 1e-9);
}

TEST_CASE("the repair refuses bad options and empty tet sets", "[repair]") {
  const TriangleSoup input = test::cube_soup();
  repair::RepairOptions options;
  REQUIRE_THROWS_AS(repair::repair_surface_from_tets(test::cube_tets(), {}, input, options), UsageError);
  options.epsilon = 1e-3;
  REQUIRE_THROWS_AS(repair::repair_surface_from_tets(TetMesh{}, {}, input, options), RunError);
  const std::vector<std::uint8_t> none_inside(test::cube_tets().tets.size(), 0);
  REQUIRE_THROWS_AS(repair::repair_surface_from_tets(test::cube_tets(), none_inside, input, options),
                    RunError);
  const std::vector<std::uint8_t> too_few(2, 1);
  REQUIRE_THROWS_AS(repair::repair_surface_from_tets(test::cube_tets(), too_few, input, options), UsageError);
  TetMesh broken = test::cube_tets();
  broken.tets[0][0] = 99;
  REQUIRE_THROWS_AS(repair::repair_surface_from_tets(broken, {}, input, options), UsageError);
}

using test::sphere;

TEST_CASE("simplify_in_envelope_of keeps the surface in the reference's envelope",
          "[repair][simplify][slow]") {
  const TriangleSoup surface = sphere(1.0, 5);
  simplify::SimplifyOptions options;
  options.epsilon_abs = 4e-3;
  const simplify::SimplifyResult own = simplify::simplify_in_envelope(surface, options);
  const simplify::SimplifyResult same = simplify::simplify_in_envelope_of(surface, surface, options);
  REQUIRE(same.soup.triangles == own.soup.triangles);
  // Every vertex of `surface` is 0.6 epsilon inside the reference: chords cut
  // inward, so most collapses the own envelope allows leave this one.
  const TriangleSoup reference = sphere(1.0 + 0.6 * options.epsilon_abs, 6);
  const simplify::SimplifyResult held = simplify::simplify_in_envelope_of(surface, reference, options);
  CAPTURE(own.faces_after, held.faces_after);
  REQUIRE(own.faces_after < surface.triangles.size() / 2);
  REQUIRE(held.faces_after > 2 * own.faces_after);
  REQUIRE(check::one_sided_distance(held.soup, reference).max <= options.epsilon_abs);
}

// ---- meshrepair end to end (needs the exact insertion of libs/tetmesh) ----

namespace {

test::ToolRun run_meshrepair(const std::vector<std::string>& args) {
  return test::run_tool(tools::meshrepair, args);
}

std::vector<char> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Binary STL: 80-byte header, count, 50 bytes a face; every stored normal
// agrees with the winding of its face, and the solid has positive volume.
void require_binary_stl_with_outward_normals(const std::filesystem::path& path) {
  const std::vector<char> bytes = file_bytes(path);
  REQUIRE(bytes.size() >= 84);
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  REQUIRE(bytes.size() == 84 + 50 * std::size_t(count));
  double six_volume = 0;
  for (std::uint32_t f = 0; f < count; ++f) {
    float v[12];
    std::memcpy(v, bytes.data() + 84 + 50 * std::size_t(f), sizeof v);
    const Vec3d n(v[0], v[1], v[2]), a(v[3], v[4], v[5]), b(v[6], v[7], v[8]), c(v[9], v[10], v[11]);
    REQUIRE(n.dot((b - a).cross(c - a)) > 0);
    six_volume += a.dot(b.cross(c));
  }
  REQUIRE(six_volume > 0);
}

struct Case {
  std::string name;
  TriangleSoup input;
  double volume;
  /// Output within epsilon of the input: not where a hole was filled
  /// (DESIGN: hole fills excepted).
  bool output_near_input = true;
  /// Input within epsilon of the output: not when input faces lie inside
  /// the solid (overlapping parts), since they are not on its boundary.
  bool input_near_output = true;
};

std::vector<Case> broken_cases() {
  TriangleSoup missing_face = test::cube_soup();
  missing_face.triangles.pop_back();
  TriangleSoup overlapping = test::cube_soup();
  overlapping.append(translated(test::cube_soup(), {0.5, 0.5, 0.5}));
  TriangleSoup inverted = test::cube_soup();
  for (Triangle& t : inverted.triangles) std::swap(t[1], t[2]);
  return {{"cube", test::cube_soup(), 1.0},
          {"cube_missing_face", missing_face, 1.0, false, true},
          {"overlapping_cubes", overlapping, 2.0 - 0.125, true, false},
          {"inverted_cube", inverted, 1.0}};
}

}  // namespace

TEST_CASE("meshrepair makes broken inputs watertight", "[repair][e2e][slow]") {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("meshrepair");
  for (const Case& c : broken_cases()) {
    SECTION(c.name) {
      const auto input = dir / (c.name + ".obj");
      io::write_surface(registry, c.input, input);
      const auto stl = dir / (c.name + "_out.stl"), stats = dir / (c.name + ".json");
      const test::ToolRun run =
          run_meshrepair({input.string(), stl.string(), "--stats", stats.string(), "-q"});
      CAPTURE(run.err);
      REQUIRE(run.exit_code == 0);
      REQUIRE(run.out.empty());
      require_binary_stl_with_outward_normals(stl);
      const TriangleSoup output = io::read_surface(registry, stl);
      const check::SurfaceReport r = check::check_surface(output);
      CAPTURE(r.boundary_edges, r.nonmanifold_edges, r.self_intersecting_pairs, r.volume);
      REQUIRE(r.watertight());
      REQUIRE(r.volume == Approx(c.volume).epsilon(0.01));

      std::ifstream stats_file(stats);
      const nlohmann::json j = nlohmann::json::parse(stats_file);
      REQUIRE(j["output"]["watertight"] == true);
      REQUIRE(j["output"]["genus"] == 0);
      const double epsilon = j["epsilon_abs"].get<double>();
      if (c.input_near_output)
        REQUIRE(j["output"]["hausdorff_input_to_output"].get<double>() <= epsilon * 1.01);
      if (c.output_near_input)
        REQUIRE(j["output"]["hausdorff_output_to_input"].get<double>() <= epsilon * 1.01);
      REQUIRE(j["input"].contains("self_intersecting_pairs"));
      REQUIRE(j["stages"].size() >= 4);
    }
  }
}

TEST_CASE("meshrepair --remesh simplifies its input first unless told not to", "[repair][e2e][slow]") {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("meshrepair_simplify");
  // A flat square plate, densely tessellated on its large faces.
  const TriangleSoup plate = test::torus_grid(40, 4, [](int i, int j) {
    const double x = i < 10 ? i / 10.0 : i < 20 ? 1.0 : i < 30 ? (30 - i) / 10.0 : 0.0;
    const double y = i < 10 ? 0.0 : i < 20 ? (i - 10) / 10.0 : i < 30 ? 1.0 : (40 - i) / 10.0;
    return Vec3d(x * (j == 1 || j == 2 ? 1.0 : 0.9) + (j == 1 || j == 2 ? 0.0 : 0.05),
                 y * (j == 1 || j == 2 ? 1.0 : 0.9) + (j == 1 || j == 2 ? 0.0 : 0.05), j < 2 ? 0.0 : 0.2);
  });
  const auto input = dir / "plate.obj";
  io::write_surface(registry, plate, input);
  const auto simplify_faces = [&](const std::vector<std::string>& extra) {
    const auto out = dir / "out.stl", stats = dir / "stats.json";
    std::vector<std::string> args{input.string(), out.string(), "--stats", stats.string(), "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::ToolRun run = run_meshrepair(args);
    CAPTURE(run.err);
    REQUIRE(run.exit_code == 0);
    REQUIRE(check::check_surface(io::read_surface(registry, out)).watertight());
    std::ifstream stats_file(stats);
    const nlohmann::json j = nlohmann::json::parse(stats_file);
    for (const nlohmann::json& stage : j["stages"]) {
      if (stage["name"] == "simplify") return stage["counts"]["faces"].get<std::int64_t>();
    }
    FAIL("no simplify stage in the stats");
    return std::int64_t{0};
  };
  const auto faces = static_cast<std::int64_t>(plate.triangles.size());
  CHECK(simplify_faces({"--remesh", "--skip-simplify"}) == faces);
  CHECK(simplify_faces({"--remesh"}) < faces / 2);
  // Without --remesh a clean closed input is written back as it is.
  const auto kept = dir / "kept.stl", kept_stats = dir / "kept.json";
  REQUIRE(run_meshrepair({input.string(), kept.string(), "--stats", kept_stats.string(), "-q"}).exit_code ==
          0);
  std::ifstream kept_file(kept_stats);
  const nlohmann::json j = nlohmann::json::parse(kept_file);
  CHECK(j["path"] == "hole_fill");
  CHECK(j["output"]["faces"] == faces);
  CHECK(j["provenance"]["kept_area_share"] == 1.0);
}

TEST_CASE("meshrepair GLB output passes the Khronos validator", "[repair][e2e]") {
  const std::filesystem::path tools_dir = test::tools_dir();
  if (std::system("node --version > /dev/null 2>&1") != 0) FAIL("node is not on PATH");
  REQUIRE(std::filesystem::exists(tools_dir / "node_modules" / "gltf-validator"));
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("meshrepair_glb");
  const auto input = dir / "overlapping.obj", glb = dir / "out.glb";
  TriangleSoup overlapping = test::cube_soup();
  overlapping.append(translated(test::cube_soup(), {0.5, 0.5, 0.5}));
  io::write_surface(registry, overlapping, input);
  const test::ToolRun run = run_meshrepair({input.string(), glb.string(), "-q"});
  CAPTURE(run.err);
  REQUIRE(run.exit_code == 0);
  std::string command = "node '";
  command += (tools_dir / "validate_gltf.mjs").string();
  command += "' '";
  command += glb.string();
  command += "' > '";
  command += (dir / "report.txt").string();
  command += "' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream report_file(dir / "report.txt");
  const std::string report{std::istreambuf_iterator<char>(report_file), std::istreambuf_iterator<char>()};
  CAPTURE(report);
  REQUIRE(status == 0);
  REQUIRE(check::check_surface(io::read_surface(registry, glb)).watertight());
}

TEST_CASE("meshrepair reports bad input and usage with exit code 2", "[repair]") {
  test::TempDir dir("meshrepair_bad");
  const auto missing = dir / "missing.stl";
  test::ToolRun run = run_meshrepair({missing.string(), (dir / "out.stl").string()});
  REQUIRE(run.exit_code == 2);
  REQUIRE(run.err.find(missing.string()) != std::string::npos);
  REQUIRE(dir.files().empty());
  run = run_meshrepair({"only_one_argument.stl"});
  REQUIRE(run.exit_code == 2);
  run = run_meshrepair({"a.stl", "b.stl", "-e", "not-a-number"});
  REQUIRE(run.exit_code == 2);
  run = run_meshrepair({"--help"});
  REQUIRE(run.exit_code == 0);
  REQUIRE(run.out.find("--stats") != std::string::npos);
}

namespace {

// The families users send (bench/make_families.py makes them from the
// corpus): every triangle unwelded and shuffled, corners rotated; when
// `defects`, a tenth of the triangles stored twice and then a twentieth of
// all faces flipped.
TriangleSoup as_soup(const TriangleSoup& welded, unsigned seed, bool defects) {
  std::mt19937 random(seed);
  std::vector<Triangle> faces = welded.triangles;
  if (defects) {
    for (const Triangle& t : welded.triangles)
      if (random() % 10 == 0) faces.push_back(t);
    for (Triangle& t : faces)
      if (random() % 20 == 0) std::swap(t[1], t[2]);
  }
  std::shuffle(faces.begin(), faces.end(), random);
  TriangleSoup soup;
  for (const Triangle& t : faces) {
    const auto first = static_cast<Index>(soup.positions.size());
    const int rotation = static_cast<int>(random() % 3);
    for (int k = 0; k < 3; ++k) soup.positions.push_back(welded.positions[t[(k + rotation) % 3]]);
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  return soup;
}

void require_watertight_glb(const TriangleSoup& input, const std::string& name,
                            const std::vector<std::string>& options = {}) {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("meshrepair_" + name);
  const auto in = dir / (name + ".stl"), out = dir / (name + ".glb"), stats = dir / "stats.json";
  io::write_surface(registry, input, in);
  std::vector<std::string> args{in.string(), out.string(), "-q", "--stats", stats.string()};
  args.insert(args.end(), options.begin(), options.end());
  const test::ToolRun run = run_meshrepair(args);
  CAPTURE(run.err);
  REQUIRE(run.exit_code == 0);
  const check::SurfaceReport r = check::check_surface(io::read_surface(registry, out));
  CAPTURE(check::watertight_failures(r));
  REQUIRE(r.watertight());
  std::ifstream stats_file(stats);
  const nlohmann::json j = nlohmann::json::parse(stats_file);
  const double epsilon = j["epsilon_abs"].get<double>();
  CAPTURE(epsilon, j["output"]["hausdorff_output_to_input"], j["output"]["hausdorff_input_to_output"]);
  REQUIRE(j["output"]["hausdorff_input_to_output"].get<double>() <= 1.01 * epsilon);
  REQUIRE(j["output"]["hausdorff_output_to_input"].get<double>() <= 1.01 * epsilon);
}

}  // namespace

TEST_CASE("meshrepair makes a soup of a sphere watertight in GLB", "[repair][e2e][slow]") {
  require_watertight_glb(as_soup(sphere(1.0, 3), 7, false), "soup");
}

TEST_CASE("meshrepair makes a soup with duplicated and flipped triangles watertight in GLB",
          "[repair][e2e][slow]") {
  // By default the copies are dropped and the flipped faces turned back
  // (the holes-only path); --remesh sends them through the tetrahedra.
  const std::vector<std::string> options =
      GENERATE(std::vector<std::string>{}, std::vector<std::string>{"--remesh"});
  for (unsigned seed : {8u, 9u, 10u}) {
    CAPTURE(seed, options);
    require_watertight_glb(as_soup(sphere(1.0, 3), seed, true), "soup_dup_flip", options);
  }
}

TEST_CASE("meshrepair makes a jittered sphere watertight in GLB", "[repair][e2e][slow]") {
  const TriangleSoup s = sphere(1.0, 4);
  require_watertight_glb(test::jittered(s, 0.5e-3 * bounding_box_diagonal(s), 9), "jitter");
}
