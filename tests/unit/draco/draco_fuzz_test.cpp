// Hostile input: random bytes and damaged copies of valid encodings must
// decode to a consistent soup or throw InputError naming the source.

#include "draco_test_support.h"

#include <mr/core/errors.h>
#include <mr/io/file_bytes.h>
#include <mr/io/mesh_io.h>
#include <mr/plugins/draco_codec.h>
#include <mr/plugins/draco_formats.h>

#include <catch2/catch.hpp>

#include <cstring>
#include <limits>
#include <random>

using namespace mr;
using namespace mr::draco_test;

namespace {

/// 0 = decoded to a consistent soup, 1 = InputError; anything else fails the test.
int decode_outcome(const std::vector<char>& bytes) {
  try {
    const TriangleSoup soup = plugins::decode_draco(std::string_view(bytes.data(), bytes.size()), "fuzz.drc");
    const std::string problem = find_soup_inconsistency(soup);
    INFO(problem);
    CHECK(problem.empty());
    return 0;
  } catch (const InputError& error) {
    CHECK(error.path() == "fuzz.drc");
    return 1;
  }
}

std::vector<char> random_bytes(std::mt19937& rng, bool draco_header) {
  std::vector<char> bytes;
  if (draco_header) {
    // "DRACO", version 2.2, triangular mesh, sequential or edgebreaker, flags.
    bytes = {'D',
             'R',
             'A',
             'C',
             'O',
             2,
             2,
             1,
             static_cast<char>(rng() % 2),
             0,
             static_cast<char>(rng() % 2 ? 0x80 : 0)};
  }
  const std::size_t length = rng() % 300;
  for (std::size_t i = 0; i < length; ++i) bytes.push_back(static_cast<char>(rng()));
  return bytes;
}

std::vector<char> damaged(const std::vector<char>& valid, std::mt19937& rng) {
  std::vector<char> bytes = valid;
  const unsigned kind = rng() % 3;
  if (kind != 1) bytes.resize(rng() % bytes.size());  // truncate
  if (kind != 0 && !bytes.empty())
    for (unsigned flips = 1 + rng() % 8; flips > 0; --flips)
      bytes[rng() % bytes.size()] ^= static_cast<char>(1u << (rng() % 8));
  return bytes;
}

TriangleSoup fuzz_model() {
  TriangleSoup soup = cube_with_attributes();
  soup.append(cube_with_attributes());  // a second cube on top of the first: duplicate faces
  TriangleSoup grid = make_grid(6, 5, 0.3);
  grid.normals.assign(grid.num_vertices(), Vec3f(0, 0, 1));
  grid.uvs.assign(grid.num_vertices(), Vec2f(0.25f, 0.5f));
  grid.colors.assign(grid.num_vertices(), Vec4f(1, 0, 0, 1));
  soup.append(grid);
  soup.face_regions.resize(soup.num_triangles());
  for (std::size_t f = 0; f < soup.num_triangles(); ++f)
    soup.face_regions[f] = static_cast<std::int32_t>(f % 3);
  return soup;
}

}  // namespace

TEST_CASE("draco decoder survives random bytes", "[draco][fuzz]") {
  std::mt19937 rng(20240601);
  int rejected = 0;
  for (int i = 0; i < 200; ++i) rejected += decode_outcome(random_bytes(rng, i % 2 == 1));
  CHECK(rejected > 150);  // random bytes are almost never a mesh
}

TEST_CASE("draco decoder survives truncated and bit-flipped encodings", "[draco][fuzz]") {
  const TriangleSoup model = fuzz_model();
  std::mt19937 rng(7);
  for (int speed : {0, 10}) {  // edgebreaker and sequential encodings
    io::DracoOptions options;
    options.speed = speed;
    const plugins::DracoEncoded valid = plugins::encode_draco(model, options);
    REQUIRE(decode_outcome(valid.bytes) == 0);
    int rejected = 0;
    for (int i = 0; i < 100; ++i) rejected += decode_outcome(damaged(valid.bytes, rng));
    CHECK(rejected > 0);
  }
}

TEST_CASE("damaged .drc files with face regions read or fail cleanly", "[draco][fuzz]") {
  io::Registry registry;
  plugins::register_draco_formats(registry);
  test::TempDir dir("draco_fuzz");
  io::write_surface(registry, fuzz_model(), dir / "valid.drc");
  const std::vector<char> valid = io::read_file_bytes(dir / "valid.drc");
  std::mt19937 rng(99);
  for (int i = 0; i < 60; ++i) {
    const std::vector<char> bytes = damaged(valid, rng);
    test::write_bytes(dir / "bad.drc", bytes);
    try {
      const TriangleSoup soup = io::read_surface(registry, dir / "bad.drc");
      CHECK((!soup.has_face_regions() || soup.face_regions.size() == soup.num_triangles()));
    } catch (const InputError& error) {
      CHECK_THAT(error.what(), Catch::Contains("bad.drc"));
    }
  }
}

namespace {

void append_varint(std::vector<char>& bytes, std::uint32_t value) {
  for (; value >= 0x80; value >>= 7) bytes.push_back(static_cast<char>((value & 0x7f) | 0x80));
  bytes.push_back(static_cast<char>(value));
}

void append_name(std::vector<char>& bytes, const std::string& name) {
  bytes.push_back(static_cast<char>(name.size()));
  bytes.insert(bytes.end(), name.begin(), name.end());
}

// An edgebreaker mesh header (bitstream 2.2) claiming `count` vertices,
// faces and symbols, optionally after metadata with a nested block.
std::vector<char> claiming_edgebreaker(std::uint32_t count, bool with_metadata) {
  std::vector<char> bytes = {
      'D', 'R', 'A', 'C', 'O', 2, 2, 1, 1, 0, static_cast<char>(with_metadata ? 0x80 : 0)};
  if (with_metadata) {
    append_varint(bytes, 1);  // one attribute's metadata
    append_varint(bytes, 0);  // its unique id
    append_varint(bytes, 1);  // one entry
    append_name(bytes, "name");
    append_varint(bytes, 11);
    for (char c : std::string("face_region")) bytes.push_back(c);
    append_varint(bytes, 0);  // no sub-blocks
    append_varint(bytes, 0);  // the geometry's: no entries,
    append_varint(bytes, 1);  // one sub-block,
    append_name(bytes, "sub");
    append_varint(bytes, 0);  // empty
    append_varint(bytes, 0);
  }
  bytes.push_back(0);           // standard traversal
  append_varint(bytes, count);  // encoded vertices
  append_varint(bytes, count);  // faces
  bytes.push_back(0);           // attribute data
  append_varint(bytes, count);  // symbols
  append_varint(bytes, 0);      // split symbols
  bytes.resize(bytes.size() + 40, 0);
  return bytes;
}

}  // namespace

TEST_CASE("a Draco mesh claiming more faces than its bytes can hold is refused before decoding",
          "[draco][fuzz]") {
  // The fuzzer's find: 73 bytes claiming 16 million faces made the decoder
  // allocate 15 GB before it failed.
  for (bool with_metadata : {false, true}) {
    const std::vector<char> bytes = claiming_edgebreaker(16'000'000, with_metadata);
    try {
      plugins::decode_draco(std::string_view(bytes.data(), bytes.size()), "claims.drc");
      FAIL("decoded");
    } catch (const InputError& error) {
      CHECK_THAT(error.what(), Catch::Contains("claims 16000000 elements"));
    }
  }
  // A 5-byte varint whose bits past 32 Draco drops (the fuzzer's 36-byte file
  // that took 23 GB): 0xFD 0xFF 0xFF 0xFE 0x44 is read as 0x4FDFFFFD faces.
  std::vector<char> long_varint = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 1, 0, 0, 0, 0};
  for (int b : {0xFD, 0xFF, 0xFF, 0xFE, 0x44}) long_varint.push_back(static_cast<char>(b));
  long_varint.resize(36, static_cast<char>(0xC5));
  CHECK_THROWS_WITH(
      plugins::decode_draco(std::string_view(long_varint.data(), long_varint.size()), "long.drc"),
      Catch::Contains("claims 1340080125 elements"));
  // Counts a file of that size can hold go on to the decoder (which rejects these bytes).
  const std::vector<char> small = claiming_edgebreaker(100, true);
  try {
    plugins::decode_draco(std::string_view(small.data(), small.size()), "small.drc");
  } catch (const InputError& error) {
    CHECK_THAT(error.what(), !Catch::Contains("claims"));
  }
}

TEST_CASE("a Draco mesh that keeps the decoder busy is refused after its CPU limit", "[draco][fuzz]") {
  // Draco's portable texture-coordinate prediction reads its number of
  // orientations as an unbounded int32 and decodes that many bits: set to
  // 2^31 - 1, a few hundred bytes kept the decoder busy for 9 s (fuzzer
  // find). The field's place depends on everything before it, so every
  // 32-bit word that could be a count is raised in turn; the one that is
  // must end in the limit's message, any other in a soup or an InputError.
  TriangleSoup grid = make_grid(12, 10, 0.3);
  for (const Vec3d& p : grid.positions) grid.uvs.emplace_back(float(p.x() / 12), float(p.y() / 10));
  io::DracoOptions options;
  options.speed = 0;  // edgebreaker with the mesh predictions, uvs among them
  const plugins::DracoEncoded valid = plugins::encode_draco(grid, options);
  REQUIRE(decode_outcome(valid.bytes) == 0);
  int words = 0, stopped = 0;
  for (std::size_t at = 0; at + 4 <= valid.bytes.size(); ++at) {
    std::int32_t word = 0;
    std::memcpy(&word, valid.bytes.data() + at, 4);
    if (word < 1 || word > static_cast<std::int32_t>(grid.num_vertices())) continue;
    ++words;
    std::vector<char> bytes = valid.bytes;
    const std::int32_t huge = std::numeric_limits<std::int32_t>::max();
    std::memcpy(bytes.data() + at, &huge, 4);
    try {
      const TriangleSoup soup =
          plugins::decode_draco(std::string_view(bytes.data(), bytes.size()), "busy.drc");
      CHECK(find_soup_inconsistency(soup).empty());
    } catch (const InputError& error) {
      CHECK(error.path() == "busy.drc");
      if (std::string(error.what()).find("did not finish within 1.0 s of CPU time") != std::string::npos)
        ++stopped;
    }
  }
  INFO(words << " words raised");
  CHECK(stopped == 1);
}
