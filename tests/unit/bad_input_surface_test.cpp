// Hostile and broken STL, OBJ, PLY and OFF files, each run through
// format-convert in-process: exit code 2, a message naming the file and the
// problem, no output file, no crash and no allocation sized from a bad count.

#include "file_checks.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>

using namespace mr;

namespace {

std::vector<char> binary_stl(std::uint32_t claimed, std::size_t facets_present, std::size_t file_size = 0) {
  std::vector<char> bytes(std::max(file_size, 84 + 50 * facets_present), 7);
  std::memcpy(bytes.data(), "binary", 6);
  std::memcpy(bytes.data() + 80, &claimed, 4);
  return bytes;
}

std::string ply_header(const std::string& format, const std::string& vertex_count,
                       const std::string& face_count) {
  return "ply\nformat " + format + " 1.0\nelement vertex " + vertex_count +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + face_count +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

}  // namespace

TEST_CASE("bad input: empty STL", "[openmesh][bad_input]") {
  test::expect_text_rejected("empty.stl", "", "empty");
}

TEST_CASE("bad input: truncated binary STL", "[openmesh][bad_input]") {
  test::TempDir dir("bad_stl_trunc");
  std::vector<char> bytes = binary_stl(4, 4);
  bytes.resize(bytes.size() - 30);
  test::write_bytes(dir / "truncated.stl", bytes);
  test::expect_rejected(dir / "truncated.stl", "claims 4 facets");
}

TEST_CASE("bad input: binary STL claiming more facets than it holds", "[openmesh][bad_input]") {
  test::TempDir dir("bad_stl_count");
  test::write_bytes(dir / "more.stl", binary_stl(100, 3));
  test::expect_rejected(dir / "more.stl", "claims 100 facets");
  test::write_bytes(dir / "huge.stl", binary_stl(0x80000000u, 0, 1024));
  test::expect_rejected(dir / "huge.stl", "claims 2147483648 facets");
}

TEST_CASE("bad input: ASCII STL with garbage", "[openmesh][bad_input]") {
  test::expect_text_rejected("garbage.stl",
                             "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 zero 0\n",
                             "'zero' is not a number");
  test::expect_text_rejected("words.stl",
                             "solid x\nthis is not an stl file at all, just some text that is long enough\n",
                             "expected 'facet'");
}

TEST_CASE("bad input: OBJ face index out of range", "[openmesh][bad_input]") {
  test::expect_text_rejected("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "index 4 out of range");
  test::expect_text_rejected("negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
                             "index -4 out of range");
}

TEST_CASE("bad input: OBJ face index 0", "[openmesh][bad_input]") {
  test::expect_text_rejected("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "index 0");
}

TEST_CASE("bad input: OBJ with NaN or Inf coordinates", "[openmesh][bad_input]") {
  test::expect_text_rejected("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "not finite");
  test::expect_text_rejected("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n", "not finite");
}

TEST_CASE("bad input: PLY claiming 2^31 vertices in 1 KB", "[openmesh][bad_input]") {
  test::TempDir dir("bad_ply_count");
  for (const std::string format : {"binary_little_endian", "ascii"}) {
    std::string text = ply_header(format, "2147483648", "1");
    text.resize(1024, '1');
    test::write_text(dir / (format + ".ply"), text);
    test::expect_rejected(dir / (format + ".ply"), "claims 2147483648 entries");
  }
}

TEST_CASE("bad input: PLY with a truncated binary body", "[openmesh][bad_input]") {
  std::string text = ply_header("binary_little_endian", "3", "1");
  text.append(36, '\0');  // three vertices
  text += '\3';
  text.append(6, '\0');  // half of the indices
  test::expect_text_rejected("truncated.ply", text, "truncated");
}

TEST_CASE("bad input: PLY face index out of range", "[openmesh][bad_input]") {
  test::expect_text_rejected("index.ply", ply_header("ascii", "3", "1") + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                             "refers to vertex 3");
  test::expect_text_rejected("negative.ply",
                             ply_header("ascii", "3", "1") + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
                             "index -1 out of range");
}

TEST_CASE("bad input: OFF with huge counts", "[openmesh][bad_input]") {
  test::expect_text_rejected("huge.off", "OFF\n2147483648 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                             "claims 2147483648 vertices");
  test::expect_text_rejected("list.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2147483648 0 1 2\n",
                             "fewer indices than its count");
}

TEST_CASE("bad input: truncated OFF", "[openmesh][bad_input]") {
  const std::string vertices = "0.25 0.25 0.25\n1.25 0.25 0.25\n0.25 1.25 0.25\n1.25 1.25 0.25\n";
  test::expect_text_rejected("truncated.off", "OFF\n4 2 0\n" + vertices + "3 0 1 2\n3 1 3",
                             "missing face vertex index");
  test::expect_text_rejected("short.off", "OFF\n4 1 0\n" + vertices, "ends before all faces");
  test::expect_text_rejected("claims.off", "OFF\n4 9 0\n" + vertices, "claims 4 vertices and 9 faces");
}
