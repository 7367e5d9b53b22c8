// Hostile .vdb files (issue 25): the walk of vdb_declared_sizes.h follows
// OpenVDB's reading of real files byte for byte, and refuses the stated sizes
// OpenVDB would trust. Files are written here by OpenVDB itself; the bytes to
// corrupt are found through the walk and the layout OpenVDB writes.

#include "test_support.h"
#include "vdb_declared_sizes.h"

#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <catch2/catch.hpp>

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>

namespace mr {
namespace {

using plugins::vdb::VdbWalk;
using plugins::vdb::walk_vdb_file;
using plugins::vdb::WalkedGrid;

constexpr std::uint32_t kZip = openvdb::io::COMPRESS_ZIP, kActiveMask = openvdb::io::COMPRESS_ACTIVE_MASK,
                        kBlosc = openvdb::io::COMPRESS_BLOSC;

enum class Writer { stream, file };

// A level set sphere of radius 20 voxels, by default across the 8 root
// children around the origin. OpenVDB drops zip compression for level
// sets, so a zip-compressed variant is of unknown class (our reader takes
// those too).
openvdb::FloatGrid::Ptr sphere(bool half, std::uint32_t compression, float center = 0.1f) {
  openvdb::initialize();
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(center), 0.05f);
  grid->setName("surface");
  grid->setSaveFloatAsHalf(half);
  if (compression & kZip) grid->setGridClass(openvdb::GRID_UNKNOWN);
  return grid;
}

std::string write_bytes(const openvdb::GridPtrVec& grids, std::uint32_t compression, Writer writer,
                        const test::TempDir& dir) {
  if (writer == Writer::stream) {
    std::ostringstream out(std::ios::binary);
    openvdb::io::Stream stream(out);
    stream.setCompression(compression);
    stream.write(grids);
    return out.str();
  }
  const std::string path = (dir / "written.vdb").string();
  openvdb::io::File file(path);
  file.setCompression(compression);
  file.write(grids);
  file.close();
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

VdbWalk walk(std::string_view bytes) { return walk_vdb_file(bytes, "test.vdb"); }

TriangleSoup read_ours(const std::string& bytes) {
  return io::read_surface_bytes(io::make_default_registry(), bytes, "test.vdb");
}

// The problem our reader reports for `bytes`, which it must refuse.
std::string refusal(const std::string& bytes) {
  try {
    read_ours(bytes);
  } catch (const InputError& e) {
    CHECK(e.path() == "test.vdb");
    return e.problem();
  }
  FAIL("read");
  return {};
}

// The mesh of the first grid as OpenVDB reads the bytes without our walk.
void check_reads_as_openvdb_does(const std::string& bytes) {
  std::istringstream in(bytes, std::ios::binary);
  openvdb::io::Stream stream(in, false);
  const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(stream.getGrids()->front());
  REQUIRE(grid);
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*grid, points, triangles, quads, 0.0, 0.0);
  const TriangleSoup ours = read_ours(bytes);
  REQUIRE(ours.positions.size() == points.size());
  CHECK(ours.triangles.size() == triangles.size() + 2 * quads.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    CHECK(ours.positions[i] == Vec3d(points[i].x(), points[i].y(), points[i].z()));
}

template <typename T>
void put(std::string& bytes, std::size_t at, T value) {
  REQUIRE(at + sizeof(T) <= bytes.size());
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

template <typename T>
T get(const std::string& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  return value;
}

// The first leaf's value buffer (io::readCompressedValues, io::writeData):
// where its int64 chunk length is, and the bytes its node expects.
struct LeafChunk {
  std::size_t length_at;
  std::uint64_t expected;
};

LeafChunk first_leaf_chunk(const std::string& bytes, const WalkedGrid& grid, std::uint32_t compression,
                           std::size_t value_bytes, std::size_t stored_bytes) {
  std::size_t at = grid.buffers_at;
  std::uint64_t active = 0;
  for (std::size_t word = 0; word < 8; ++word)
    active += static_cast<std::uint64_t>(std::popcount(get<std::uint64_t>(bytes, at + 8 * word)));
  at += 64;
  const auto flag = get<std::int8_t>(bytes, at++);
  if (flag == 2 || flag == 4) at += value_bytes;  // one inactive value
  if (flag == 5) at += 2 * value_bytes;
  if (flag >= 3 && flag <= 5) at += 64;  // selection mask
  const std::uint64_t count = (compression & kActiveMask) && flag != 6 ? active : 512;
  return {at, count * stored_bytes};
}

// A tree's root counts: after the tree's buffer count and the background.
std::size_t root_tile_count_at(const WalkedGrid& grid, std::size_t value_bytes) {
  return grid.tree_at + 4 + value_bytes;
}

struct Variant {
  std::uint32_t compression;
  bool half;
  Writer writer;
};

std::vector<Variant> variants() {
  std::vector<Variant> all;
  for (const std::uint32_t compression :
       {0u, kActiveMask, kZip, kZip | kActiveMask, kBlosc, kBlosc | kActiveMask})
    for (const bool half : {false, true})
      for (const Writer writer : {Writer::stream, Writer::file}) all.push_back({compression, half, writer});
  return all;
}

std::string describe(const Variant& v) {
  return "compression " + std::to_string(v.compression) + (v.half ? ", half" : "") +
         (v.writer == Writer::stream ? ", io::Stream" : ", io::File");
}

}  // namespace

TEST_CASE("vdb: files OpenVDB writes walk to their end and read as OpenVDB reads them", "[vdb]") {
  test::TempDir dir("vdb_walk_valid");
  for (const Variant& v : variants()) {
    INFO(describe(v));
    const auto grid = sphere(v.half, v.compression);
    const std::string bytes = write_bytes({grid}, v.compression, v.writer, dir);
    const VdbWalk walked = walk(bytes);
    CHECK(walked.walked);
    CHECK(walked.end == bytes.size());
    REQUIRE(walked.grids.size() == 1);
    CHECK(walked.grids[0].name == "surface");
    CHECK(walked.grids[0].type == std::string("Tree_float_5_4_3") + (v.half ? "_HalfFloat" : ""));
    CHECK(walked.grids[0].leaves == grid->tree().leafCount());
    check_reads_as_openvdb_does(bytes);
  }
}

TEST_CASE("vdb: a file of many grids, value types, tiles, instances and transforms walks exactly", "[vdb]") {
  test::TempDir dir("vdb_walk_many");
  openvdb::initialize();
  openvdb::GridPtrVec grids{sphere(false, 0)};
  // Leaves whose inactive values need each flag of io::readCompressedValues (background 1).
  auto odd = openvdb::FloatGrid::create(1.0f);
  odd->setName("odd inactive values");
  auto& tree = odd->tree();
  const auto leaf_at = [](int i) { return openvdb::CoordBBox::createCube(openvdb::Coord(8 * i, 0, 0), 8); };
  tree.setValueOn(openvdb::Coord(0, 0, 0), 2.0f);  // the rest at the background: flag 0
  tree.fill(leaf_at(1), -1.0f, false);             // all at -background: flag 1
  tree.setValueOn(leaf_at(1).min(), 2.0f);
  tree.fill(leaf_at(2), 7.0f, false);  // all at one other value: flag 2
  tree.setValueOn(leaf_at(2).min(), 2.0f);
  tree.setValueOff(leaf_at(3).min(), -1.0f);  // +-background: flag 3
  tree.setValueOff(leaf_at(4).min(), 7.0f);   // background and one other: flag 4
  tree.fill(leaf_at(5), 7.0f, false);         // two others: flag 5
  tree.setValueOff(leaf_at(5).min(), 8.0f);
  for (int i = 0; i < 3; ++i) tree.setValueOff(leaf_at(6).min().offsetBy(i), 3.0f + float(i));  // flag 6
  grids.push_back(odd);
  auto doubles = openvdb::DoubleGrid::create(0.0);
  doubles->setName("doubles");
  doubles->setSaveFloatAsHalf(true);
  doubles->tree().fill(openvdb::CoordBBox(openvdb::Coord(-5), openvdb::Coord(20)), 3.0, true);
  grids.push_back(doubles);
  auto ints = openvdb::Int32Grid::create(0);
  ints->setName("ints");
  ints->setSaveFloatAsHalf(true);  // not a real type: saved in full all the same
  ints->tree().fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(4095)), 7, true);  // a root tile
  ints->tree().setValue(openvdb::Coord(5000, 1, 2), 9);
  grids.push_back(ints);
  auto longs = openvdb::Int64Grid::create(0);
  longs->setName("longs");
  longs->tree().setValue(openvdb::Coord(-3, 4, 5), 1);
  grids.push_back(longs);
  auto vec3s = openvdb::Vec3SGrid::create();
  vec3s->setName("vec3s");
  vec3s->setSaveFloatAsHalf(true);
  vec3s->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1, 2, 3));
  grids.push_back(vec3s);
  auto vec3d = openvdb::Vec3DGrid::create();
  vec3d->setName("vec3d");
  vec3d->tree().setValue(openvdb::Coord(9, 2, 3), openvdb::Vec3d(1, 2, 3));
  vec3d->setTransform(openvdb::math::Transform::createFrustumTransform(
      openvdb::BBoxd(openvdb::Vec3d(0), openvdb::Vec3d(10)), 0.5, 2));
  grids.push_back(vec3d);
  auto vec3i = openvdb::Vec3IGrid::create();
  vec3i->setName("vec3i");
  vec3i->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3i(1, 2, 3));
  grids.push_back(vec3i);
  auto instance = grids[0]->copyGrid();  // shares the sphere's tree: written as an instance
  instance->setName("instance");
  grids.push_back(instance);
  for (const std::uint32_t compression : {0u, kZip | kActiveMask, kBlosc | kActiveMask})
    for (const Writer writer : {Writer::stream, Writer::file}) {
      INFO("compression " << compression << (writer == Writer::stream ? ", io::Stream" : ", io::File"));
      const std::string bytes = write_bytes(grids, compression, writer, dir);
      const VdbWalk walked = walk(bytes);
      CHECK(walked.end == bytes.size());
      REQUIRE(walked.grids.size() == grids.size());
      for (std::size_t g = 0; g < grids.size(); ++g) {
        INFO("grid " << grids[g]->getName());
        CHECK(walked.grids[g].name == grids[g]->getName());
        CHECK(walked.grids[g].instance == (g + 1 == grids.size()));
        if (!walked.grids[g].instance) CHECK(walked.grids[g].leaves == grids[g]->baseTree().leafCount());
      }
      check_reads_as_openvdb_does(bytes);
    }
}

TEST_CASE("vdb: stated buffer sizes that do not fit are refused before OpenVDB reads them", "[vdb]") {
  test::TempDir dir("vdb_walk_sizes");
  for (const std::uint32_t compression : {kZip | kActiveMask, kZip, kBlosc | kActiveMask, kBlosc})
    for (const bool half : {false, true}) {
      INFO("compression " << compression << (half ? ", half" : ""));
      const std::string bytes = write_bytes({sphere(half, compression)}, compression, Writer::stream, dir);
      const WalkedGrid grid = walk(bytes).grids.at(0);
      const LeafChunk chunk = first_leaf_chunk(bytes, grid, compression, 4, half ? 2 : 4);
      REQUIRE(chunk.expected > 0);

      // A raw length longer than the node's buffer: OpenVDB would read it all into the buffer.
      std::string overflow = bytes;
      put<std::int64_t>(overflow, chunk.length_at, -static_cast<std::int64_t>(chunk.expected + 64));
      CHECK_THAT(refusal(overflow), Catch::Contains("corrupt OpenVDB file: leaf values are stated as " +
                                                    std::to_string(chunk.expected + 64) + " raw bytes"));
      std::string shorter = bytes;
      put<std::int64_t>(shorter, chunk.length_at, -static_cast<std::int64_t>(chunk.expected - 1));
      CHECK_THAT(refusal(shorter), Catch::Contains("raw bytes where the node holds"));
      put<std::int64_t>(shorter, chunk.length_at, std::numeric_limits<std::int64_t>::min());
      CHECK_THAT(refusal(shorter), Catch::Contains("raw bytes where the node holds"));

      // A compressed length past the end: OpenVDB would allocate it first.
      std::string past_end = bytes;
      put<std::int64_t>(past_end, chunk.length_at, std::int64_t{1} << 32);
      CHECK_THAT(refusal(past_end),
                 Catch::Contains("leaf values claim a compressed chunk of 4294967296 bytes"));

      if (!(compression & kBlosc)) continue;
      const std::int64_t length = get<std::int64_t>(bytes, chunk.length_at);
      REQUIRE(length > 16);
      const std::size_t header = chunk.length_at + 8;
      std::string wrong_size = bytes;
      put<std::uint32_t>(wrong_size, header + 4, static_cast<std::uint32_t>(chunk.expected + 4));
      CHECK_THAT(refusal(wrong_size), Catch::Contains("uncompressed where the node holds"));
      std::string long_chunk = bytes;
      put<std::uint32_t>(long_chunk, header + 12, static_cast<std::uint32_t>(length + 100));
      CHECK_THAT(refusal(long_chunk), Catch::Contains("claiming " + std::to_string(length + 100)));
      std::string short_chunk = bytes;
      put<std::int64_t>(short_chunk, chunk.length_at, 15);
      CHECK_THAT(refusal(short_chunk), Catch::Contains("shorter than a Blosc header"));
    }
}

TEST_CASE("vdb: root tile and child counts the file cannot hold are refused", "[vdb]") {
  test::TempDir dir("vdb_walk_root");
  const std::string bytes =
      write_bytes({sphere(false, kBlosc | kActiveMask)}, kBlosc | kActiveMask, Writer::stream, dir);
  const WalkedGrid grid = walk(bytes).grids.at(0);
  const std::size_t tiles_at = root_tile_count_at(grid, 4);
  REQUIRE(get<std::uint32_t>(bytes, tiles_at) == 0);  // a sphere's root holds children only
  REQUIRE(get<std::uint32_t>(bytes, tiles_at + 4) > 0);

  std::string tiles = bytes;
  put<std::uint32_t>(tiles, tiles_at, 0xFFFFFFF0u);
  CHECK_THAT(refusal(tiles), Catch::Contains("the root node claims 4294967280 tiles"));
  std::string children = bytes;
  put<std::uint32_t>(children, tiles_at + 4, 0xFFFFFFF0u);
  CHECK_THAT(refusal(children), Catch::Contains("the root node claims 4294967280 children"));
  std::string misplaced = bytes;
  put<std::int32_t>(misplaced, tiles_at + 8, get<std::int32_t>(bytes, tiles_at + 8) + 1);
  CHECK_THAT(refusal(misplaced), Catch::Contains("not the origin of a node"));

  // The first child's values, after its origin and its two masks: stated longer than the node holds.
  const std::size_t flag_at = tiles_at + 8 + 12 + 2 * 4096;
  REQUIRE(get<std::int8_t>(bytes, flag_at) >= 0);
  REQUIRE(get<std::int8_t>(bytes, flag_at) <= 6);
  std::string unknown_flag = bytes;
  put<std::int8_t>(unknown_flag, flag_at, 7);
  CHECK_THAT(refusal(unknown_flag),
             Catch::Contains("internal node values carry an unknown compression flag 7"));
}

TEST_CASE("vdb: delayed-load metadata claiming more leaves than the file holds is refused", "[vdb]") {
  test::TempDir dir("vdb_walk_delayed");
  const std::string bytes =
      write_bytes({sphere(false, kBlosc | kActiveMask)}, kBlosc | kActiveMask, Writer::file, dir);
  const std::string type = "__delayedload";
  const std::size_t type_at = bytes.find(type);
  REQUIRE(type_at != std::string::npos);
  const std::size_t size_at = type_at + type.size(), count_at = size_at + 4;
  REQUIRE(get<std::uint32_t>(bytes, count_at) == walk(bytes).grids.at(0).leaves);
  std::string many = bytes;
  put<std::uint32_t>(many, count_at, 0xFFFFFFF0u);
  CHECK_THAT(refusal(many), Catch::Contains("delayed-load metadata claims 4294967280 leaves"));
  std::string small = bytes;
  put<std::uint32_t>(small, size_at, 9);  // the count and part of the next length
  CHECK_THAT(refusal(small), Catch::Contains("the stated size of delayed-load metadata ends"));
}

TEST_CASE("vdb: a file cut anywhere is refused by the walk, and read as an input error", "[vdb]") {
  test::TempDir dir("vdb_walk_cut");
  for (const std::uint32_t compression : {0u, kZip, kBlosc | kActiveMask}) {
    // In one root child: each of the cuts walks the tree up to it.
    const std::string bytes =
        write_bytes({sphere(compression == 0, compression, 1.5f)}, compression, Writer::file, dir);
    INFO("compression " << compression << ", " << bytes.size() << " bytes");
    std::vector<std::size_t> walked_through;  // cut sizes the walk did not refuse
    for (std::size_t size = 0; size < bytes.size(); ++size) {
      try {
        walk(std::string_view(bytes).substr(0, size));
        walked_through.push_back(size);
      } catch (const InputError&) {
      }
    }
    CHECK(walked_through.empty());
    for (std::size_t size = 1; size < bytes.size(); size += bytes.size() / 61) {
      INFO("cut to " << size);
      CHECK_THAT(refusal(bytes.substr(0, size)), Catch::Contains("OpenVDB file"));
    }
  }
}

TEST_CASE("vdb: damaged copies read to a mesh or an input error", "[vdb]") {
  test::TempDir dir("vdb_walk_damaged");
  const std::string bytes =
      write_bytes({sphere(false, kBlosc | kActiveMask)}, kBlosc | kActiveMask, Writer::stream, dir);
  std::mt19937 random(25);
  for (int round = 0; round < 300; ++round) {
    std::string damaged = bytes;
    for (int flips = 1 + static_cast<int>(random() % 4); flips > 0; --flips)
      damaged[random() % damaged.size()] ^= static_cast<char>(1u << (random() % 8));
    try {
      read_ours(damaged);
    } catch (const InputError& e) {
      CHECK(e.path() == "test.vdb");
    }
  }
}

TEST_CASE("vdb: a grid of a type the walk does not follow is refused, naming it", "[vdb]") {
  test::TempDir dir("vdb_walk_types");
  openvdb::initialize();
  auto mask = openvdb::BoolGrid::create(false);
  mask->setName("inside");
  mask->tree().setValue(openvdb::Coord(1, 2, 3), true);
  const std::string bytes = write_bytes({sphere(false, 0), mask}, kBlosc | kActiveMask, Writer::file, dir);
  const std::string problem = refusal(bytes);
  CHECK_THAT(problem, Catch::Contains("\"inside\"") && Catch::Contains("Tree_bool_5_4_3"));
  CHECK_THROWS_WITH(walk(bytes), Catch::Contains("\"inside\""));
}

TEST_CASE("vdb: format versions before 222 are refused, later ones walked as OpenVDB 10 reads them",
          "[vdb]") {
  test::TempDir dir("vdb_walk_versions");
  const std::string bytes =
      write_bytes({sphere(false, kBlosc | kActiveMask)}, kBlosc | kActiveMask, Writer::stream, dir);
  REQUIRE(get<std::uint32_t>(bytes, 8) == 224);
  std::string old = bytes;
  put<std::uint32_t>(old, 8, 221);
  CHECK_THAT(refusal(old), Catch::Contains("format version 221"));
  std::string later = bytes;
  put<std::uint32_t>(later, 8, 225);
  CHECK(walk(later).end == later.size());
  CHECK(read_ours(later).triangles.size() == read_ours(bytes).triangles.size());
}

}  // namespace mr
