#include "test_support.h"
#include "tetrahedralize.h"

#include <mr/check/surface_check.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>

namespace mr {
namespace {

// Every edge is used once in each direction: closed, consistently oriented
// and edge-manifold.
bool is_closed_and_oriented(const TriangleSoup& soup) {
  std::map<std::pair<Index, Index>, int> directed;
  for (const Triangle& t : soup.triangles)
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    const auto opposite = directed.find({edge.second, edge.first});
    if (count != 1 || opposite == directed.end() || opposite->second != 1) return false;
  }
  return !soup.triangles.empty();
}

// Distance from p to the surface of the box [lo, hi]^3.
double distance_to_box_surface(const Vec3d& p, double lo, double hi) {
  const Vec3d outside = (Vec3d::Constant(lo) - p).cwiseMax(p - Vec3d::Constant(hi)).cwiseMax(0.0);
  if (outside.squaredNorm() > 0) return outside.norm();
  return std::min((p - Vec3d::Constant(lo)).minCoeff(), (Vec3d::Constant(hi) - p).minCoeff());
}

double max_distance_to_box(const TriangleSoup& soup, double lo, double hi) {
  double worst = 0.0;
  for (const Vec3d& p : soup.positions) worst = std::max(worst, distance_to_box_surface(p, lo, hi));
  return worst;
}

TriangleSoup round_trip(const TriangleSoup& soup, const std::filesystem::path& file, double voxel,
                        double adaptivity = 0.0) {
  const io::Registry registry = io::make_default_registry();
  io::WriteOptions write;
  write.level_set.voxel_size = voxel;
  io::write_surface(registry, soup, file, write);
  io::ReadOptions read;
  read.level_set.adaptivity = adaptivity;
  return io::read_surface(registry, file, read);
}

std::vector<char> read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The bytes of the unit cube written as a level set with this voxel size.
std::vector<char> cube_vdb_bytes(const std::filesystem::path& file, double voxel) {
  io::WriteOptions write;
  write.level_set.voxel_size = voxel;
  io::write_surface(io::make_default_registry(), test::cube_soup(), file, write);
  return read_all(file);
}

}  // namespace

TEST_CASE("a cube round-trips through a level set", "[vdb]") {
  test::TempDir dir("vdb_cube");
  const double voxel = 0.02;
  const TriangleSoup back = round_trip(test::cube_soup(), dir / "cube.vdb", voxel);
  CHECK(is_closed_and_oriented(back));
  CHECK(test::enclosed_volume(back) == Approx(1.0).epsilon(0.03));
  CHECK(max_distance_to_box(back, 0.0, 1.0) < 1.5 * voxel);
}

TEST_CASE("a box's level set reads back watertight once identical positions are welded", "[vdb]") {
  // At the box's edges and corners volumeToMesh gives polygons two corners
  // at one position; read as faces, they left 786 zero-area faces on the
  // unit cube and format-convert refused to write any box as .vdb.
  test::TempDir dir("vdb_box");
  for (const Vec3d& sides : {Vec3d(1, 1, 1), Vec3d(20, 60, 10)}) {
    TriangleSoup box = test::cube_soup();
    for (Vec3d& p : box.positions) p = p.cwiseProduct(sides);
    const TriangleSoup back = round_trip(box, dir / "box.vdb", 0.0);
    const check::SurfaceReport report = check::check_surface(back);
    INFO("box " << sides.transpose() << ": " << check::watertight_failures(report));
    CHECK(report.watertight());
    CHECK(is_closed_and_oriented(back));
  }
}

TEST_CASE("the default voxel size is the bounding box diagonal / 256", "[vdb]") {
  test::TempDir dir("vdb_default");
  const TriangleSoup back = round_trip(test::cube_soup(0, 2), dir / "cube.vdb", 0.0);
  const double voxel = std::sqrt(12.0) / 256.0;
  CHECK(is_closed_and_oriented(back));
  CHECK(test::enclosed_volume(back) == Approx(8.0).epsilon(0.03));
  CHECK(max_distance_to_box(back, 0.0, 2.0) < 1.5 * voxel);
}

TEST_CASE("an open cube still gives a closed surface, signed by the winding number", "[vdb]") {
  test::TempDir dir("vdb_open");
  TriangleSoup open = test::cube_soup();
  open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4);  // the z = 1 face
  const double voxel = 0.02;
  const TriangleSoup back = round_trip(open, dir / "open.vdb", voxel);
  CHECK(is_closed_and_oriented(back));
  CHECK(test::enclosed_volume(back) == Approx(1.0).epsilon(0.05));
  CHECK(max_distance_to_box(back, 0.0, 1.0) < 2.0 * voxel);
}

TEST_CASE("an inconsistent, self-intersecting soup gives the union of its solids", "[vdb][slow]") {
  test::TempDir dir("vdb_union");
  TriangleSoup soup = test::cube_soup(0, 1);
  soup.append(test::cube_soup(0.5, 1.5));
  std::swap(soup.triangles[5][1], soup.triangles[5][2]);  // one face flipped
  const TriangleSoup back = round_trip(soup, dir / "union.vdb", 0.02);
  CHECK(is_closed_and_oriented(back));
  CHECK(test::enclosed_volume(back) == Approx(2.0 - 0.125).epsilon(0.05));
}

TEST_CASE("a soup oriented inward throughout still gives an outward solid", "[vdb]") {
  test::TempDir dir("vdb_inward");
  TriangleSoup inward = test::cube_soup();
  for (Triangle& t : inward.triangles) std::swap(t[1], t[2]);
  const TriangleSoup back = round_trip(inward, dir / "inward.vdb", 0.02);
  CHECK(is_closed_and_oriented(back));
  CHECK(test::enclosed_volume(back) == Approx(1.0).epsilon(0.03));
}

TEST_CASE("adaptivity 0.5 gives fewer triangles than 0", "[vdb]") {
  test::TempDir dir("vdb_adaptive");
  const TriangleSoup uniform = round_trip(test::cube_soup(), dir / "cube.vdb", 0.02, 0.0);
  const io::Registry registry = io::make_default_registry();
  io::ReadOptions read;
  read.level_set.adaptivity = 0.5;
  const TriangleSoup adaptive = io::read_surface(registry, dir / "cube.vdb", read);
  CHECK(adaptive.num_triangles() > 0);
  CHECK(adaptive.num_triangles() < uniform.num_triangles() / 2);
  CHECK(test::enclosed_volume(adaptive) == Approx(1.0).epsilon(0.05));
}

TEST_CASE("invalid level set options are usage errors", "[vdb]") {
  test::TempDir dir("vdb_options");
  const io::Registry registry = io::make_default_registry();
  io::WriteOptions write;
  write.level_set.voxel_size = -1;
  CHECK_THROWS_AS(io::write_surface(registry, test::cube_soup(), dir / "a.vdb", write), UsageError);
  write.level_set.voxel_size = 1e-7;  // far too many voxels
  CHECK_THROWS_AS(io::write_surface(registry, test::cube_soup(), dir / "a.vdb", write), UsageError);
  write.level_set.voxel_size = 0.1;
  write.level_set.half_width = 0.5;
  CHECK_THROWS_AS(io::write_surface(registry, test::cube_soup(), dir / "a.vdb", write), UsageError);
  CHECK(dir.files().empty());
}

TEST_CASE("garbage .vdb input is exit 2 naming the file, with no output", "[vdb]") {
  test::TempDir dir("vdb_garbage");
  const auto in = dir / "garbage.vdb";
  test::write_text(in, "this is not an OpenVDB file at all, just some text to fill it up");
  const test::ToolRun run = test::run_format_convert({in.string(), (dir / "out.stl").string()});
  CHECK(run.exit_code == 2);
  CHECK(run.err.find(in.string()) != std::string::npos);
  CHECK(dir.files() == std::vector<std::string>{"garbage.vdb"});
}

TEST_CASE("truncated .vdb files are input errors naming the file", "[vdb]") {
  test::TempDir dir("vdb_truncated");
  const io::Registry registry = io::make_default_registry();
  const std::vector<char> bytes = cube_vdb_bytes(dir / "cube.vdb", 0.1);
  REQUIRE(bytes.size() > 200);
  const auto cut_file = dir / "cut.vdb";
  for (std::size_t size = 1; size < bytes.size(); size += std::max<std::size_t>(1, bytes.size() / 97)) {
    INFO("truncated to " << size << " of " << bytes.size() << " bytes");
    test::write_bytes(cut_file, std::vector<char>(bytes.begin(), bytes.begin() + static_cast<long>(size)));
    try {
      io::read_surface(registry, cut_file);
      FAIL("a truncated file was read");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find(cut_file.string()) != std::string::npos);
    }
  }
}

TEST_CASE("a .vdb without a float grid is an input error", "[vdb]") {
  test::TempDir dir("vdb_int_grid");
  const io::Registry registry = io::make_default_registry();
  io::write_surface(registry, test::cube_soup(), dir / "cube.vdb");
  std::vector<char> bytes = read_all(dir / "cube.vdb");
  // Same size values: relabelling the tree type keeps the file readable.
  const std::string from = "Tree_float_5_4_3", to = "Tree_int32_5_4_3";
  auto at = std::search(bytes.begin(), bytes.end(), from.begin(), from.end());
  REQUIRE(at != bytes.end());
  for (; at != bytes.end(); at = std::search(at, bytes.end(), from.begin(), from.end()))
    std::copy(to.begin(), to.end(), at);
  test::write_bytes(dir / "int.vdb", bytes);
  try {
    io::read_surface(registry, dir / "int.vdb");
    FAIL("a file without float grids was read");
  } catch (const InputError& e) {
    CHECK(e.path() == (dir / "int.vdb").string());
    CHECK(e.problem().find("float") != std::string::npos);
  }
}

TEST_CASE("a level set with an active tile is refused before it is meshed", "[vdb]") {
  // A level set keeps its narrow band of voxels active; an active tile
  // would be meshed on every side where the sign changes.
  openvdb::initialize();
  test::TempDir dir("vdb_active_tile");
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(3.0f);
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  grid->setName("surface");
  grid->tree().addTile(/*level=*/1, openvdb::Coord(0, 0, 0), -3.0f, /*active=*/true);
  {
    std::ofstream out(dir / "tile.vdb", std::ios::binary);
    openvdb::io::Stream(out).write(openvdb::GridCPtrVec{grid});
  }
  const io::Registry registry = io::make_default_registry();
  try {
    io::read_surface(registry, dir / "tile.vdb");
    FAIL("a level set with an active tile was meshed");
  } catch (const InputError& e) {
    CHECK(e.problem().find("active tiles") != std::string::npos);
  }
}

}  // namespace mr

namespace mr {

TEST_CASE("writing a level set is deterministic, whatever the thread count", "[vdb][slow]") {
  test::TempDir dir("vdb_determinism");
  const io::Registry registry = io::make_default_registry();
  TriangleSoup open = test::cube_soup();
  open.triangles.pop_back();  // a hole, so the hole-spanning band is exercised too
  io::write_surface(registry, open, dir / "a.vdb");
  io::write_surface(registry, open, dir / "b.vdb");
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    io::write_surface(registry, open, dir / "c.vdb");
  }
  const std::vector<char> a = read_all(dir / "a.vdb");
  CHECK(a.size() > 100);
  CHECK(a == read_all(dir / "b.vdb"));
  CHECK(a == read_all(dir / "c.vdb"));
}

TEST_CASE("a .vdb stating a name or metadata longer than the file is refused before reading it", "[vdb]") {
  // The fuzzer's find: OpenVDB allocated and filled a 4 GB name from a tiny file.
  test::TempDir dir("vdb_lengths");
  const io::Registry registry = io::make_default_registry();
  const std::vector<char> bytes = cube_vdb_bytes(dir / "cube.vdb", 0.25);
  const auto patch_length_before = [&](const std::string& text, const char* what) {
    const std::string all(bytes.begin(), bytes.end());
    const std::size_t at = all.find(text);
    REQUIRE(at != std::string::npos);
    REQUIRE(at >= 4);
    std::vector<char> patched = bytes;
    const std::uint32_t huge = 0xFFFFFFF0u;
    std::memcpy(patched.data() + at - 4, &huge, 4);
    const auto file = dir / "patched.vdb";
    test::write_bytes(file, patched);
    try {
      io::read_surface(registry, file);
      FAIL("read");
    } catch (const InputError& e) {
      CHECK_THAT(e.what(), Catch::Contains(std::string("the ") + what + " claims 4294967280 bytes"));
    }
  };
  patch_length_before("surface", "grid name");
  patch_length_before("Tree_float", "grid type");
  patch_length_before("level set", "metadata value");
  // A fixed-size value whose stated size differs (OpenVDB would read 4 bytes and go on out of step).
  std::string retyped(bytes.begin(), bytes.end());
  const std::size_t vec3i = retyped.find("vec3i");
  REQUIRE(vec3i != std::string::npos);
  retyped.replace(vec3i, 5, "int32");
  test::write_bytes(dir / "retyped.vdb", std::vector<char>(retyped.begin(), retyped.end()));
  CHECK_THROWS_WITH(io::read_surface(registry, dir / "retyped.vdb"),
                    Catch::Contains("holds 12 bytes, not 4"));
  CHECK(round_trip(test::cube_soup(), dir / "again.vdb", 0.25).triangles.size() > 0);
}

}  // namespace mr

namespace mr {
namespace {

// A dense float grid named `name` of value 0.1 over [-0.2, 1.2]^3 (voxels
// of 0.1), written with OpenVDB itself, as a user's tool would.
void write_sizing_grid(const std::filesystem::path& path, const std::string& name) {
  openvdb::initialize();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName(name);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
  grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(-2), openvdb::Coord(12)), 0.1f, true);
  openvdb::io::File file(path.string());
  file.write({grid});
  file.close();
}

}  // namespace

TEST_CASE("vdb: a float grid reads as a scalar field, NaN away from its active voxels", "[vdb][sizing]") {
  test::TempDir dir("vdb_field");
  const io::Registry registry = io::make_default_registry();
  write_sizing_grid(dir / "sizing.vdb", "lengths");
  const io::Format* vdb = registry.by_name("vdb");
  REQUIRE(vdb != nullptr);
  REQUIRE(vdb->read_field);
  const std::shared_ptr<const ScalarField> field = vdb->read_field(dir / "sizing.vdb");
  CHECK(field->at(Vec3d(0.53, 0.5, 0.21)) == Approx(0.1));
  CHECK(std::isnan(field->at(Vec3d(5, 5, 5))));
  CHECK_THROWS_AS(vdb->read_field(dir / "missing.vdb"), InputError);

  // A level set is no field of lengths, unless named "sizing".
  io::WriteOptions write;
  write.level_set.voxel_size = 0.05;
  io::write_surface(registry, test::cube_soup(), dir / "cube.vdb", write);
  CHECK_THROWS_WITH(vdb->read_field(dir / "cube.vdb"), Catch::Contains("level set"));
}

TEST_CASE("tetrahedralize --sizing takes an OpenVDB float grid", "[vdb][sizing][tool]") {
  test::TempDir dir("vdb_sizing_tool");
  const io::Registry registry = io::make_default_registry();
  write_sizing_grid(dir / "sizing.vdb", "sizing");
  const auto cube = dir / "cube.obj";
  io::write_surface(registry, test::cube_soup(), cube);
  const auto coarse = dir / "coarse.msh", fine = dir / "fine.msh";
  const std::vector<std::string> common = {"-q", "--lattice", "0", "--edge-length-abs", "0.4"};
  auto args = [&](const std::filesystem::path& out) {
    std::vector<std::string> all = {cube.string(), out.string()};
    all.insert(all.end(), common.begin(), common.end());
    return all;
  };
  REQUIRE(test::run_tool(tools::tetrahedralize, args(coarse)).exit_code == 0);
  std::vector<std::string> with_field = args(fine);
  with_field.insert(with_field.end(), {"--sizing", (dir / "sizing.vdb").string()});
  const test::ToolRun run = test::run_tool(tools::tetrahedralize, with_field);
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK(io::read_volume(registry, fine).tets.size() > 20 * io::read_volume(registry, coarse).tets.size());

  io::WriteOptions write;
  write.level_set.voxel_size = 0.05;
  io::write_surface(registry, test::cube_soup(), dir / "cube.vdb", write);
  std::vector<std::string> level_set = args(dir / "bad.msh");
  level_set.insert(level_set.end(), {"--sizing", (dir / "cube.vdb").string()});
  const test::ToolRun refused = test::run_tool(tools::tetrahedralize, level_set);
  CHECK(refused.exit_code == 2);
  CHECK_THAT(refused.err, Catch::Contains("cube.vdb") && Catch::Contains("level set"));
}

}  // namespace mr
