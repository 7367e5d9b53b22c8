// meshrepair's minimal change: input triangles away from defects come out
// as they went in, and every output face knows where it came from.

#include "mesh_generators.h"
#include "test_support.h"

#include <mr/check/provenance.h>
#include <mr/check/surface_check.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/repair/attribute_transfer.h>
#include <mr/simplify/simplify.h>
#include <mr/spatial/improper_meetings.h>
#include <mr/tetmesh/insertion.h>
#include <mr/tetmesh/tetrahedralize.h>

#include <fast_path.h>
#include <meshrepair.h>

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>

using namespace mr;

namespace {

using CornerSet = std::array<std::array<double, 3>, 3>;

CornerSet corner_set(const TriangleSoup& soup, std::size_t f) {
  CornerSet set;
  for (int i = 0; i < 3; ++i) {
    const Vec3d& p = soup.positions[soup.triangles[f][i]];
    set[i] = {p.x(), p.y(), p.z()};
  }
  std::sort(set.begin(), set.end());
  return set;
}

std::set<CornerSet> faces_of(const TriangleSoup& soup) {
  std::set<CornerSet> faces;
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) faces.insert(corner_set(soup, f));
  return faces;
}

TriangleSoup translated(TriangleSoup soup, const Vec3d& offset) {
  for (Vec3d& p : soup.positions) p += offset;
  return soup;
}

// Positions rounded to float32, so that STL and GLB store them exactly. (Not
// with p = p.cast<float>().cast<double>(): in a loop over Vec3d's, GCC 12's
// SLP vectorizer drops the round trip at -O2 and -O3.)
TriangleSoup as_floats(TriangleSoup soup) {
  const CoordinateGrid floats = CoordinateGrid::float32();
  for (Vec3d& p : soup.positions) p = floats.nearest(p);
  return soup;
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

// Two unit spheres overlapping by a fifth of their diameter: the union's
// surface has an intersection curve and a lens of faces inside the other.
struct OverlappingSpheres {
  TriangleSoup a = as_floats(test::sphere(1.0, 4));
  TriangleSoup b = as_floats(translated(test::sphere(1.0, 4), {1.6, 0.05, 0.03}));
  Vec3d centre_b{1.6, 0.05, 0.03};

  TriangleSoup both() const {
    TriangleSoup soup = a;
    soup.append(b);
    return soup;
  }
};

}  // namespace

TEST_CASE("meshrepair keeps the input triangles away from an intersection, bit for bit in GLB",
          "[repair][keep][e2e]") {
  const io::Registry registry = io::make_default_registry();
  const test::TempDir dir("meshrepair_keep");
  const OverlappingSpheres spheres;
  const TriangleSoup input = spheres.both();
  io::write_surface(registry, input, dir / "in.stl");
  const test::ToolRun run = test::run_tool(
      tools::meshrepair, {(dir / "in.stl").string(), (dir / "out.glb").string(), "--stats",
                          (dir / "s.json").string(), "--provenance", (dir / "p.json").string()});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const TriangleSoup output = io::read_surface(registry, dir / "out.glb");
  REQUIRE(check::check_surface(output).watertight());
  const nlohmann::json stats = read_json(dir / "s.json");
  const double epsilon = stats["epsilon_abs"];
  REQUIRE(stats["keep_input_band_rings"] == 0);  // only the faces that meet others were simplified

  // Every triangle of sphere a that no face of b cuts and whose corners are
  // outside b (hence all of it: b is convex and inside the unit ball) is an
  // output face as it was, those beside the intersection curve included:
  // only the faces that meet another improperly are simplified.
  const std::vector<std::uint8_t> cut = spatial::faces_meeting_others(input);
  const std::set<CornerSet> out_faces = faces_of(output);
  std::size_t outside = 0, beside_cut = 0, inside = 0;
  for (std::size_t f = 0; f < spheres.a.triangles.size(); ++f) {
    double nearest = 1e300, farthest = 0.0;
    for (Index v : spheres.a.triangles[f]) {
      const double d = (spheres.a.positions[v] - spheres.centre_b).norm();
      nearest = std::min(nearest, d), farthest = std::max(farthest, d);
    }
    if (nearest > 1.0 && !cut[f]) {
      ++outside;
      beside_cut += nearest < 1.0 + 2.0 * epsilon;
      REQUIRE(out_faces.count(corner_set(spheres.a, f)) == 1);
    } else if (farthest < 0.99) {
      ++inside;  // inside b: not part of the union's surface
      REQUIRE(out_faces.count(corner_set(spheres.a, f)) == 0);
    }
  }
  REQUIRE(outside > spheres.a.triangles.size() / 2);
  REQUIRE(beside_cut > 0);
  REQUIRE(inside > 0);

  // The provenance file follows the written faces; kept faces name an input
  // triangle with the same corners.
  const nlohmann::json provenance = read_json(dir / "p.json");
  REQUIRE(provenance["faces"] == output.triangles.size());
  REQUIRE(provenance["input_face"].size() == output.triangles.size());
  std::size_t kept = 0;
  for (std::size_t f = 0; f < output.triangles.size(); ++f) {
    const std::int64_t source = provenance["input_face"][f];
    if (provenance["source"][f] == "kept") {
      ++kept;
      REQUIRE(corner_set(output, f) == corner_set(input, static_cast<std::size_t>(source)));
    } else {
      REQUIRE(provenance["source"][f] == "recut");  // no hole: nothing filled
      REQUIRE(source >= 0);
    }
  }
  REQUIRE(stats["provenance"]["kept_faces"] == kept);
  REQUIRE(stats["provenance"]["kept_area_share"].get<double>() > 0.9);
}

TEST_CASE("keeping the input widens the band around defects, then rebuilds, as its tet budget says",
          "[repair][keep]") {
  const TriangleSoup input = OverlappingSpheres().both();
  const tetmesh::TetrahedralizeOptions defaults = tools::repair_defaults();
  tools::RepairTetsOptions options;
  tools::RepairTets tets =
      tools::tetrahedralize_for_repair(input, defaults, tools::RebuildMode::keep_input, options);
  REQUIRE(tets.mode == tools::RebuildMode::keep_input);
  REQUIRE(tets.band_rings == 0);
  REQUIRE(tets.gave_way.empty());

  options.tet_budget = 10;
  std::vector<std::string> told;
  options.on_give_way = [&](const std::string& why, const std::string&) { told.push_back(why); };
  tets = tools::tetrahedralize_for_repair(input, defaults, tools::RebuildMode::keep_input, options);
  REQUIRE(tets.mode == tools::RebuildMode::remesh);
  REQUIRE(tets.band_rings == -1);
  REQUIRE(tets.gave_way.size() == tools::kKeepInputBands.size());
  REQUIRE(told == tets.gave_way);
  REQUIRE(!tets.pipeline.mesh.tets.empty());

  options.keep_or_nothing = true;  // the widest band runs without a budget
  tets = tools::tetrahedralize_for_repair(input, defaults, tools::RebuildMode::keep_input, options);
  REQUIRE(tets.mode == tools::RebuildMode::keep_input);
  REQUIRE(tets.band_rings == tools::kKeepInputBands.back());
  REQUIRE(tets.gave_way.size() == tools::kKeepInputBands.size() - 1);
}

TEST_CASE("a band with every face near a defect is inserted without the tet budget", "[repair][keep]") {
  // Open triangles fanned around the z axis, each crossing the others: every
  // face is a defect, so band 0 simplifies them all, as a rebuild would.
  TriangleSoup input;
  constexpr int kTriangles = 8;
  for (int i = 0; i < kTriangles; ++i) {
    const double a = 3.14159 * i / kTriangles;
    const Index first = static_cast<Index>(input.positions.size());
    input.positions.push_back({std::cos(a), std::sin(a), -1.0});
    input.positions.push_back({-std::cos(a), -std::sin(a), -1.0});
    input.positions.push_back({-0.3 * std::sin(a), 0.3 * std::cos(a), 1.0});
    input.triangles.push_back({first, first + 1, first + 2});
  }
  tools::RepairTetsOptions options;
  options.tet_budget = 10;  // far below what any insertion needs
  const tools::RepairTets tets = tools::tetrahedralize_for_repair(input, tools::repair_defaults(),
                                                                  tools::RebuildMode::keep_input, options);
  REQUIRE(tets.gave_way.empty());
  REQUIRE(tets.mode == tools::RebuildMode::keep_input);
  REQUIRE(tets.band_rings == 0);
  REQUIRE(tets.pipeline.mesh.tets.size() > 10);
}

TEST_CASE("meshrepair --remesh rebuilds every face", "[repair][keep][e2e]") {
  const io::Registry registry = io::make_default_registry();
  const test::TempDir dir("meshrepair_remesh");
  io::write_surface(registry, OverlappingSpheres().both(), dir / "in.stl");
  const test::ToolRun run =
      test::run_tool(tools::meshrepair, {(dir / "in.stl").string(), (dir / "out.stl").string(), "--remesh",
                                         "--stats", (dir / "s.json").string(), "-q"});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const nlohmann::json stats = read_json(dir / "s.json");
  // Rebuilt inside the envelope: hardly any input triangle is left as it was.
  CHECK(stats["provenance"]["kept_area_share"].get<double>() < 0.1);
}

TEST_CASE("meshrepair keeps a clean closed input as it is at any size", "[repair][keep][e2e]") {
  const io::Registry registry = io::make_default_registry();
  const test::TempDir dir("meshrepair_clean");
  // 128 faces, and 131,072: above the size where inputs with defects are
  // rebuilt by default.
  const int subdivisions = GENERATE(2, 7);
  const TriangleSoup input = as_floats(test::sphere(1.0, subdivisions));
  io::write_surface(registry, input, dir / "in.stl");
  const test::ToolRun run = test::run_tool(
      tools::meshrepair,
      {(dir / "in.stl").string(), (dir / "out.glb").string(), "--stats", (dir / "s.json").string()});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const std::set<CornerSet> out = faces_of(io::read_surface(registry, dir / "out.glb")), in = faces_of(input);
  std::size_t common = 0;
  for (const CornerSet& f : in) common += out.count(f);
  // Equal sets, compared by counts: a failed `out == in` would print every face.
  REQUIRE(common == in.size());
  REQUIRE(out.size() == in.size());
  REQUIRE(read_json(dir / "s.json")["provenance"]["kept_area_share"] == 1.0);
}

TEST_CASE("meshrepair refuses --provenance for Draco output", "[repair][keep]") {
  const io::Registry registry = io::make_default_registry();
  const test::TempDir dir("meshrepair_provenance_draco");
  io::write_surface(registry, test::cube_soup(), dir / "in.obj");
  for (const std::vector<std::string>& target :
       {std::vector<std::string>{(dir / "out.drc").string()},
        std::vector<std::string>{(dir / "out.glb").string(), "--draco"}}) {
    std::vector<std::string> args{(dir / "in.obj").string()};
    args.insert(args.end(), target.begin(), target.end());
    args.insert(args.end(), {"--provenance", (dir / "p.json").string()});
    const test::ToolRun run = test::run_tool(tools::meshrepair, args);
    REQUIRE(run.exit_code == 2);
    REQUIRE(run.err.find("reorders faces") != std::string::npos);
    REQUIRE(!std::filesystem::exists(dir / "p.json"));
    REQUIRE(!std::filesystem::exists(target[0]));
  }
}

TEST_CASE("meshrepair --source-faces wants glTF output without Draco", "[repair][keep]") {
  const io::Registry registry = io::make_default_registry();
  const test::TempDir dir("meshrepair_source_faces");
  io::write_surface(registry, test::cube_soup(), dir / "in.obj");
  for (const std::vector<std::string>& target :
       {std::vector<std::string>{(dir / "out.obj").string()},
        std::vector<std::string>{(dir / "out.glb").string(), "--draco"}}) {
    std::vector<std::string> args{(dir / "in.obj").string(), "--source-faces"};
    args.insert(args.end(), target.begin(), target.end());
    const test::ToolRun run = test::run_tool(tools::meshrepair, args);
    CAPTURE(run.err);
    REQUIRE(run.exit_code == 2);
    REQUIRE(run.err.find("--source-faces") != std::string::npos);
    REQUIRE(!std::filesystem::exists(target[0]));
  }
}

TEST_CASE("face provenance tells kept, recut and filled faces apart", "[check][keep]") {
  TriangleSoup input;
  input.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  input.triangles = {{0, 1, 2}, {1, 3, 2}};
  TriangleSoup output;
  output.positions = {{0, 0, 0},    {1, 0, 0},     {0, 1, 0},      // input triangle 0, turned
                      {1, 1, 1e-4}, {0.9, 0.5, 0}, {0.5, 0.9, 0},  // on triangle 1, moved a little
                      {0, 0, 1},    {1, 0, 1},     {0, 1, 1}};     // far above both
  output.triangles = {{1, 2, 0}, {3, 5, 4}, {6, 7, 8}};
  const check::FaceProvenance p = check::face_provenance(output, input, CoordinateGrid::doubles(), 1e-3);
  REQUIRE(p.source == std::vector<check::FaceSource>{check::FaceSource::kept, check::FaceSource::recut,
                                                     check::FaceSource::filled});
  REQUIRE(p.input_face == std::vector<std::int64_t>{0, 1, -1});
  const check::ProvenanceSummary s = check::summarize_provenance(p, output);
  REQUIRE(s.kept_faces == 1);
  REQUIRE(s.input_triangles_kept == 1);
  REQUIRE(s.kept_area == Approx(0.5));
  REQUIRE(s.kept_area_share() == Approx(0.5 / (0.5 + s.recut_area + 0.5)));

  // Kept on the output's grid: corners that float32 rounds equal count as kept.
  TriangleSoup fine = input;
  fine.positions[1].x() = 1.0 + 1e-12;
  REQUIRE(check::face_provenance(output, fine, CoordinateGrid::float32(), 1e-3).source[0] ==
          check::FaceSource::kept);
  REQUIRE(check::face_provenance(output, fine, CoordinateGrid::doubles(), 1e-3).source[0] ==
          check::FaceSource::recut);
}

TEST_CASE("simplification leaves frozen faces as they are", "[simplify][keep]") {
  // A finely tessellated sphere: everything would coarsen, but the frozen
  // band around the equator stays face for face.
  const TriangleSoup sphere = test::sphere(1.0, 4);
  simplify::SimplifyOptions options;
  options.epsilon_rel = 1e-2;
  options.frozen_faces.resize(sphere.triangles.size());
  std::set<CornerSet> frozen;
  for (std::size_t f = 0; f < sphere.triangles.size(); ++f) {
    double z = 0.0;
    for (Index v : sphere.triangles[f]) z += sphere.positions[v].z() / 3.0;
    options.frozen_faces[f] = std::abs(z) < 0.2;
    if (options.frozen_faces[f]) frozen.insert(corner_set(sphere, f));
  }
  REQUIRE(!frozen.empty());
  const simplify::SimplifyResult result = simplify::simplify_in_envelope(sphere, options);
  REQUIRE(result.collapses > 0);
  const std::set<CornerSet> out = faces_of(result.soup);
  for (const CornerSet& face : frozen) REQUIRE(out.count(face) == 1);

  options.frozen_faces.pop_back();
  REQUIRE_THROWS_AS(simplify::simplify_in_envelope(sphere, options), UsageError);
}

TEST_CASE("simplification merges a frozen fan back into its triangle where asked", "[simplify][keep]") {
  // A sphere whose face (a, b, c) is fanned through the midpoint m of edge
  // ab, as meshrepair's put-back does when a rebuilt neighbour uses a point
  // on its edge; the neighbour (b, a, d) is split at m too.
  TriangleSoup sphere = test::sphere(1.0, 3);
  const Triangle t = sphere.triangles[0];
  const Index a = t[0], b = t[1], c = t[2];
  std::size_t neighbour = 0;
  Index d = 0;
  for (std::size_t f = 1; f < sphere.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i)
      if (sphere.triangles[f][i] == b && sphere.triangles[f][(i + 1) % 3] == a)
        neighbour = f, d = sphere.triangles[f][(i + 2) % 3];
  REQUIRE(neighbour != 0);
  const TriangleSoup whole = sphere;
  const auto m = static_cast<Index>(sphere.positions.size());
  sphere.positions.push_back((sphere.positions[a] + sphere.positions[b]) / 2.0);
  sphere.triangles[0] = {a, m, c};
  sphere.triangles.push_back({m, b, c});
  sphere.triangles[neighbour] = {b, m, d};
  sphere.triangles.push_back({m, a, d});

  simplify::SimplifyOptions options;
  options.epsilon_rel = 1e-2;
  options.frozen_faces.assign(sphere.triangles.size(), 0);
  options.frozen_faces[0] = options.frozen_faces[sphere.triangles.size() - 2] = 1;
  const CornerSet triangle = corner_set(whole, 0);
  REQUIRE(faces_of(simplify::simplify_in_envelope(sphere, options).soup).count(triangle) == 0);

  options.frozen_merges = {{m, a}, {m, b}};
  const simplify::SimplifyResult merged = simplify::simplify_in_envelope(sphere, options);
  REQUIRE(faces_of(merged.soup).count(triangle) == 1);
  REQUIRE(check::check_surface(merged.soup).watertight());

  options.frozen_merges = {{m, static_cast<Index>(sphere.positions.size())}};
  REQUIRE_THROWS_AS(simplify::simplify_in_envelope(sphere, options), UsageError);
}

TEST_CASE("attributes follow each face from the input triangle it came from", "[repair][keep]") {
  // Two input triangles meeting along an edge, a UV seam between them (each
  // has its own copies of the shared corners, with other UVs).
  TriangleSoup input;
  input.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  input.triangles = {{0, 1, 2}, {3, 4, 5}};
  input.uvs = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0.5f}, {1, 1}, {0.5f, 1}};
  input.normals.assign(6, Vec3f(0, 0, 1));
  input.face_regions = {3, 5};
  input.region_names = {"a", "b", "c", "d", "e", "f"};
  TriangleSoup output;  // the first triangle kept, a piece of the second, a face far above
  output.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.75, 0.75, 0}, {0, 0, 1}};
  output.triangles = {{0, 1, 2}, {1, 3, 4}, {5, 1, 2}};
  const std::vector<std::int64_t> source{0, 1, -1};
  const TriangleSoup dressed =
      repair::with_input_attributes(output, input, source, CoordinateGrid::doubles());

  REQUIRE(dressed.triangles.size() == 3);
  auto uv_at = [&](std::size_t f, int corner) { return dressed.uvs[dressed.triangles[f][corner]]; };
  auto position_at = [&](std::size_t f, int corner) {
    return dressed.positions[dressed.triangles[f][corner]];
  };
  for (std::size_t f = 0; f < 3; ++f)
    for (int i = 0; i < 3; ++i) REQUIRE(position_at(f, i) == output.positions[output.triangles[f][i]]);
  // Kept: the input's own UVs.
  REQUIRE(uv_at(0, 0) == Vec2f(0, 0));
  REQUIRE(uv_at(0, 1) == Vec2f(1, 0));
  REQUIRE(uv_at(0, 2) == Vec2f(0, 1));
  // On the second triangle: its corners' UVs, and (0.75, 0.75) interpolated;
  // (1, 0) is a seam: another vertex than the first face's.
  REQUIRE(uv_at(1, 0) == Vec2f(0.5f, 0.5f));
  REQUIRE(dressed.triangles[1][0] != dressed.triangles[0][1]);
  REQUIRE(uv_at(1, 1) == Vec2f(1, 1));
  REQUIRE(uv_at(1, 2).isApprox(Vec2f(0.75f, 0.875f)));
  // Filled: the input's values at the nearest point; a region of its own.
  REQUIRE(uv_at(2, 1) == Vec2f(1, 0));
  REQUIRE(dressed.normals.size() == dressed.positions.size());
  REQUIRE(dressed.face_regions == std::vector<std::int32_t>{3, 5, 6});
  REQUIRE(dressed.region_names.size() == 7);
  REQUIRE(dressed.region_names[6] == "filled");

  // A face the clean-up stretched across the seam reads its source's side
  // only: (1, 1) lies on the second triangle alone, and takes the first's
  // values at its closest point, (0.5, 0.5), not the second's (1, 1).
  TriangleSoup stretched;
  stretched.positions = {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  stretched.triangles = {{0, 1, 2}};
  const TriangleSoup across = repair::with_input_attributes(stretched, input, std::vector<std::int64_t>{0},
                                                            CoordinateGrid::doubles());
  REQUIRE(across.uvs[across.triangles[0][0]] == Vec2f(0, 0));
  REQUIRE(across.uvs[across.triangles[0][1]].isApprox(Vec2f(0.5f, 0.5f)));
  REQUIRE(across.uvs[across.triangles[0][2]] == Vec2f(0, 1));

  // Without attributes or filled faces nothing is added.
  TriangleSoup plain = input;
  plain.uvs.clear(), plain.normals.clear(), plain.face_regions.clear(), plain.region_names.clear();
  const TriangleSoup bare = repair::with_input_attributes(output, plain, std::vector<std::int64_t>{0, 1, 1},
                                                          CoordinateGrid::doubles());
  REQUIRE(bare.positions == output.positions);
  REQUIRE(!bare.has_uvs());
  REQUIRE(!bare.has_face_regions());
  REQUIRE_THROWS_AS(repair::with_input_attributes(output, plain, std::vector<std::int64_t>{0, 2, 1},
                                                  CoordinateGrid::doubles()),
                    UsageError);
}

TEST_CASE("meshrepair carries materials, their images and UVs from GLB and OBJ+MTL to GLB",
          "[repair][keep][e2e]") {
  const io::Registry registry = io::make_default_registry();
  const test::TempDir dir("meshrepair_materials");
  // Two overlapping boxes, one textured (a 2x2 PNG), one plain red.
  const std::vector<std::uint8_t> png = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52,
      0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x02, 0x00, 0x00, 0x00, 0xfd, 0xd4, 0x9a,
      0x73, 0x00, 0x00, 0x00, 0x16, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x3c, 0x21, 0x27, 0xc7,
      0xc0, 0xc0, 0xc0, 0xc4, 0xc0, 0xc0, 0xc0, 0xc0, 0xc0, 0x00, 0x00, 0x0d, 0x04, 0x01, 0x08, 0x7d,
      0x71, 0xca, 0x66, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  TriangleSoup input = test::cube_soup();
  input.face_regions.assign(input.triangles.size(), 0);
  TriangleSoup second = translated(test::cube_soup(), {0.5, 0.25, 0.125});
  second.face_regions.assign(second.triangles.size(), 1);
  input.append(second);
  for (const Vec3d& p : input.positions) input.uvs.emplace_back(float(p.x() + p.z()), float(p.y()));
  input.region_names = {"textured", "red"};
  input.images = {{"image/png", png}};
  input.materials.resize(2);
  input.materials[0].name = "textured";
  input.materials[0].base_color_image = 0;
  input.materials[1].name = "red";
  input.materials[1].base_color = {0.8f, 0.1f, 0.1f, 1.0f};
  input.materials[1].double_sided = true;
  const std::string in = GENERATE(as<std::string>(), "in.glb", "in.obj");
  CAPTURE(in);
  io::write_surface(registry, input, dir / in);
  if (in == "in.obj") {  // the library and texture beside the file, named after it
    REQUIRE(std::filesystem::exists(dir / "in.mtl"));
    REQUIRE(std::filesystem::exists(dir / "in_0.png"));
  }

  const test::ToolRun run =
      test::run_tool(tools::meshrepair,
                     {(dir / in).string(), (dir / "out.glb").string(), "--stats", (dir / "s.json").string(),
                      "--provenance", (dir / "p.json").string(), "--source-faces"});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  REQUIRE(read_json(dir / "s.json")["path"] == "tetrahedralize");
  const TriangleSoup output = io::read_surface(registry, dir / "out.glb");
  REQUIRE(check::check_surface(output).watertight());
  REQUIRE(output.materials.size() == 2);
  REQUIRE(output.materials[0].base_color_image >= 0);
  REQUIRE(output.images[static_cast<std::size_t>(output.materials[0].base_color_image)].bytes == png);
  REQUIRE(output.images[static_cast<std::size_t>(output.materials[0].base_color_image)].mime_type ==
          "image/png");
  REQUIRE(output.materials[1].base_color == input.materials[1].base_color);
  REQUIRE(output.materials[1].double_sided == (in == "in.glb"));  // MTL has no double-sidedness
  REQUIRE(output.has_uvs());
  // Every output vertex carries the UV the input's mapping gives at its place.
  for (const Triangle& t : output.triangles)
    for (Index v : t) {
      const Vec3d& p = output.positions[v];
      const Vec2f expected(float(p.x() + p.z()), float(p.y()));
      CAPTURE(p.transpose(), output.uvs[v].transpose());
      REQUIRE((output.uvs[v] - expected).norm() < 1e-5f);
    }
  // _SOURCE_FACE: the provenance file's entries, face for face in the
  // written order (faces grouped by material); a kept face is its input
  // triangle.
  const nlohmann::json provenance = read_json(dir / "p.json");
  REQUIRE(output.face_sources == provenance["input_face"].get<std::vector<std::int64_t>>());
  std::size_t kept = 0;
  for (std::size_t f = 0; f < output.triangles.size(); ++f) {
    if (provenance["source"][f] != "kept") continue;
    ++kept;
    REQUIRE(corner_set(output, f) == corner_set(input, std::size_t(output.face_sources[f])));
  }
  CHECK(kept > 0);
  const std::filesystem::path tools_dir = test::tools_dir();
  const std::string command = "node '" + (tools_dir / "validate_gltf.mjs").string() + "' '" +
                              (dir / "out.glb").string() + "' > '" + (dir / "report.txt").string() + "' 2>&1";
  REQUIRE(std::system(command.c_str()) == 0);
}

TEST_CASE("faces meeting others improperly are found exactly", "[spatial][keep]") {
  TriangleSoup soup;
  soup.positions = {{0, 0, 0},      {2, 0, 0},     {0, 2, 0},      // a
                    {0.5, 0.5, -1}, {0.5, 0.5, 1}, {1.5, 0.2, 0},  // b crosses a
                    {2, 0, 0},      {0, 2, 0},     {2, 2, 0},      // c shares a's edge
                    {5, 5, 5},      {6, 5, 5},     {5, 6, 5},      // d far away
                    {0, 0, 0},      {1, 0.5, -1},  {0.5, 1, 1},    // e shares a's corner, crosses a
                    {2, 0, 0},      {3, 0, 1},     {3, 1, 1}};     // f shares a corner of a and c only
  soup.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 8, 7}, {9, 10, 11}, {12, 13, 14}, {15, 16, 17}};
  REQUIRE(spatial::faces_meeting_others(soup) == std::vector<std::uint8_t>{1, 1, 0, 0, 1, 0});
  soup.triangles.resize(4);
  // Only asked faces are tested; skipped ones are not tested against.
  REQUIRE(spatial::faces_meeting_others(soup, std::vector<std::uint8_t>{0, 1, 1, 1}) ==
          std::vector<std::uint8_t>{0, 1, 0, 0});
  REQUIRE(spatial::faces_meeting_others(soup, {}, std::vector<std::uint8_t>{1, 0, 0, 0}) ==
          std::vector<std::uint8_t>{0, 0, 0, 0});
  // With groups, only faces of another group count: a and b cross within group 0.
  REQUIRE(spatial::faces_meeting_others(soup, {}, {}, std::vector<std::uint32_t>{0, 0, 1, 2}) ==
          std::vector<std::uint8_t>{0, 0, 0, 0});
  REQUIRE(spatial::faces_meeting_others(soup, {}, {}, std::vector<std::uint32_t>{0, 1, 1, 2}) ==
          std::vector<std::uint8_t>{1, 1, 0, 0});
  // A face with collinear corners through a is neither tested nor tested
  // against, skip list or not (it threw, from meshrepair's defect cut on a
  // soup of manifold/Offset1 with duplicated and flipped faces).
  const auto sliver = static_cast<Index>(soup.positions.size());
  soup.positions.insert(soup.positions.end(), {{0.25, 0.25, -1}, {0.25, 0.25, 0}, {0.25, 0.25, 1}});
  soup.triangles.push_back({sliver, sliver + 1, sliver + 2});
  REQUIRE(spatial::faces_meeting_others(soup, {}, {}, std::vector<std::uint32_t>{0, 1, 2, 3, 4}) ==
          std::vector<std::uint8_t>{1, 1, 0, 0, 0});
}

TEST_CASE("insertion stops past its tet budget", "[tetrahedralize][keep]") {
  // Keeping the faces (none is near a defect): max_insertion_tets bounds it.
  tetmesh::PipelineOptions options;
  options.tetrahedralize.simplify_near_defects_only = true;
  options.tetrahedralize.max_insertion_tets = 10;
  options.tetrahedralize.max_rebuild_insertion_tets = 0;
  try {
    tetmesh::tetrahedralize(test::sphere(1.0, 2), options);
    FAIL("keeping the faces did not stop at its budget");
  } catch (const tetmesh::RebuildTooCostly&) {
    FAIL("keeping the faces stopped as a rebuild");
  } catch (const tetmesh::InsertionTooCostly&) {
  }
  options.tetrahedralize.max_insertion_tets = 0;  // no limit
  REQUIRE(!tetmesh::tetrahedralize(test::sphere(1.0, 2), options).mesh.tets.empty());

  // Rebuilding every face: max_rebuild_insertion_tets bounds it, not max_insertion_tets.
  options.tetrahedralize.simplify_near_defects_only = false;
  options.tetrahedralize.max_insertion_tets = 10;
  REQUIRE(!tetmesh::tetrahedralize(test::sphere(1.0, 2), options).mesh.tets.empty());
  options.tetrahedralize.max_rebuild_insertion_tets = 10;
  REQUIRE_THROWS_AS(tetmesh::tetrahedralize(test::sphere(1.0, 2), options), tetmesh::RebuildTooCostly);
}
