#include "file_checks.h"
#include "test_support.h"

#include <mr/core/errors.h>
#include <mr/io/atomic_file.h>
#include <mr/io/file_bytes.h>
#include <mr/io/mesh_io.h>
#include <mr/io/output_file.h>
#include <mr/io/text_cursor.h>
#include <mr/io/text_encoding.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <new>
#include <stdexcept>

using namespace mr;

namespace {

// A toy format that stores only the vertex count, to test the core in isolation.
io::Registry toy_registry() {
  io::Registry registry;
  io::Format toy;
  toy.name = "toy";
  toy.extensions = {".toy"};
  toy.read_surface = [](const std::filesystem::path& path, const io::ReadOptions&) {
    std::ifstream in(path);
    int n = 0;
    in >> n;
    TriangleSoup soup;
    soup.positions.resize(n, Vec3d::Zero());
    soup.triangles.push_back({0, 1, 2});  // out of range when n < 3
    return soup;
  };
  toy.write_surface = [](const TriangleSoup& soup, const std::filesystem::path& path,
                         const io::WriteOptions&) {
    if (soup.num_vertices() == 13) throw RunError("unlucky");
    std::ofstream(path) << soup.num_vertices();
  };
  registry.add(toy);
  return registry;
}

}  // namespace

TEST_CASE("registry resolves by extension, case-insensitively, and by name", "[io]") {
  const io::Registry registry = toy_registry();
  CHECK(registry.by_extension("a/b.TOY") != nullptr);
  CHECK(registry.by_extension("a/b.obj") == nullptr);
  CHECK(&registry.resolve_for_read("x.obj", "toy") == registry.by_name("toy"));
  CHECK_THROWS_AS(registry.resolve_for_read("x.obj", ""), InputError);
  CHECK_THROWS_AS(registry.resolve_for_write("x.obj", ""), UsageError);
  CHECK_THROWS_AS(registry.resolve_for_read("x.toy", "nope"), UsageError);
  io::Registry twice = toy_registry();
  io::Format clash;
  clash.name = "other";
  clash.extensions = {".toy"};
  CHECK_THROWS_AS(twice.add(clash), std::logic_error);
}

TEST_CASE("reading checks existence, emptiness and consistency", "[io]") {
  const io::Registry registry = toy_registry();
  test::TempDir dir("io_read");
  CHECK_THROWS_WITH(io::read_surface(registry, dir / "missing.toy"), Catch::Contains("no such file"));
  test::write_text(dir / "empty.toy", "");
  CHECK_THROWS_WITH(io::read_surface(registry, dir / "empty.toy"), Catch::Contains("empty"));
  test::write_text(dir / "two.toy", "2");
  CHECK_THROWS_AS(io::read_surface(registry, dir / "two.toy"), InputError);
  test::write_text(dir / "three.toy", "3");
  CHECK(io::read_surface(registry, dir / "three.toy").num_vertices() == 3);
}

TEST_CASE("a failed write leaves neither output nor temporary file", "[io]") {
  const io::Registry registry = toy_registry();
  test::TempDir dir("io_write");
  TriangleSoup soup;
  soup.positions.resize(13, Vec3d::Zero());
  test::write_text(dir / "out.toy", "old");
  CHECK_THROWS_AS(io::write_surface(registry, soup, dir / "out.toy"), RunError);
  CHECK(dir.files() == std::vector<std::string>{"out.toy"});  // old file untouched
  soup.positions.resize(5);
  io::write_surface(registry, soup, dir / "out.toy");
  CHECK(dir.files() == std::vector<std::string>{"out.toy"});
  std::ifstream in(dir / "out.toy");
  int n = 0;
  in >> n;
  CHECK(n == 5);
}

TEST_CASE("byte reader refuses counts larger than the data", "[io]") {
  const std::vector<char> data(16, 0);
  io::ByteReader reader("f.bin", data.data(), data.size());
  CHECK(reader.read<std::uint32_t>("count") == 0);
  CHECK_NOTHROW(reader.require(3, 4, "items"));
  CHECK_THROWS_AS(reader.require(4, 4, "items"), InputError);
  CHECK_THROWS_AS(reader.require(std::uint64_t(1) << 31, 50, "triangles"), InputError);
  CHECK_THROWS_WITH(reader.seek(17, "chunk"), Catch::Contains("f.bin"));
  reader.skip(12, "rest");
  CHECK(reader.at_end());
  CHECK_THROWS_AS(reader.read<char>("one more"), InputError);
}

TEST_CASE("output file writes shortest exact numbers and little-endian values", "[io][output_file]") {
  test::TempDir dir("io_output");
  io::OutputFile out(dir / "a.bin");
  out << "x " << 0.1 << ' ' << 1.0 / 3.0 << ' ' << 0.1f << ' ' << -2e-300 << ' ' << std::int64_t{-42} << ' '
      << 7 << ' ' << std::uint32_t{4000000000u} << '\n';
  out.write_le(std::uint32_t{0x01020304});
  out.write_native(std::int16_t{-2});
  const std::string big(3 << 20, 'b');  // larger than the buffer: written directly, in order
  out.write_raw(big.data(), big.size());
  out << "end";
  out.close();
  const std::string text = test::read_text(dir / "a.bin");
  const std::string line = "x 0.1 0.3333333333333333 0.1 -2e-300 -42 7 4000000000\n";
  REQUIRE(text.size() == line.size() + 4 + 2 + big.size() + 3);
  CHECK(text.substr(0, line.size()) == line);
  CHECK(text.substr(line.size(), 4) == std::string("\x04\x03\x02\x01", 4));
  CHECK(text.substr(line.size() + 6, big.size()) == big);
  CHECK(text.ends_with("bend"));
}

TEST_CASE("output file keeps the order of small writes across buffer flushes", "[io][output_file]") {
  test::TempDir dir("io_output_flush");
  io::OutputFile out(dir / "n.txt");
  std::string expected;
  for (std::int64_t i = 0; i < 300000; ++i) {  // about 2 MB: several flushes
    out << i << ' ';
    out.write_le(std::uint16_t{0x0a41});
    expected += std::to_string(i) + " A\n";
  }
  out.close();
  CHECK(test::read_text(dir / "n.txt") == expected);
}

TEST_CASE("output file failures are RunErrors naming the file", "[io][output_file]") {
  CHECK_THROWS_WITH(io::OutputFile("/nonexistent-dir/x.off"), Catch::Contains("/nonexistent-dir/x.off"));
  CHECK_THROWS_AS(io::write_file_bytes("/nonexistent-dir/y.drc", "abc"), RunError);
  if (!std::filesystem::exists("/dev/full")) return;
  io::OutputFile full("/dev/full");
  full << "some text";
  CHECK_THROWS_WITH(full.close(), Catch::Contains("/dev/full"));
}

TEST_CASE("text cursor reads lines and tokens, naming file and line on failure", "[io][text_cursor]") {
  const std::string text = "# head\n\n  1 +2.5 x  \r\nlast 99999999999999999999";
  io::TextCursor lines("t.txt", text);
  std::string_view line;
  REQUIRE(lines.next_content_line(line, '#'));
  CHECK(line == "1 +2.5 x");
  io::Tokens tokens(line);
  CHECK(lines.integer(tokens, "count") == 1);
  CHECK(lines.number(tokens, "value") == 2.5);
  CHECK_THROWS_WITH(lines.number(tokens, "value"),
                    Catch::Contains("t.txt") && Catch::Contains("line 3") &&
                        Catch::Contains("expected a number for value, found 'x'"));
  CHECK_THROWS_WITH(lines.number(tokens, "value"), Catch::Contains("missing value"));
  REQUIRE(lines.next_line(line));
  CHECK(line == "last 99999999999999999999");
  io::Tokens last(line);
  last.next();
  CHECK_THROWS_WITH(lines.integer(last, "count"),
                    Catch::Contains("line 4") && Catch::Contains("out of range"));
  CHECK_FALSE(lines.next_line(line));

  io::TextCursor cursor("t.txt", text, '#');
  CHECK(cursor.unsigned_integer("count") == 1);
  CHECK(cursor.real("value") == 2.5);
  CHECK_THROWS_WITH(cursor.int32("tag"), Catch::Contains("line 3") && Catch::Contains("found 'x'"));
  CHECK_THROWS_WITH(cursor.expect("first"), Catch::Contains("line 4") && Catch::Contains("found 'last'"));
  CHECK_THROWS_WITH(cursor.signed_integer("n"), Catch::Contains("n '99999999999999999999' is out of range"));
  CHECK(cursor.at_end());
  CHECK_THROWS_WITH(cursor.token("node"), Catch::Contains("unexpected end of file while reading node"));
}

TEST_CASE("text cursor never reads past the end and checks counts before allocation", "[io][text_cursor]") {
  const std::string text = "$Nodes\n2147483648\n\x01\x02\x03";
  io::TextCursor cursor("n.msh", text);
  cursor.expect("$Nodes");
  const std::uint64_t count = cursor.unsigned_integer("node count");
  cursor.skip_line();
  CHECK_THROWS_WITH(cursor.require(count, 4, "$Nodes"),
                    Catch::Contains("n.msh") && Catch::Contains("declares 2147483648"));
  CHECK_NOTHROW(cursor.require(1, 3, "$Nodes"));
  CHECK_THROWS_AS(cursor.raw<std::uint32_t>("node"), InputError);
  CHECK(cursor.raw<std::uint16_t>("node") == 0x0201);
  CHECK_THROWS_AS(cursor.take(2, "node"), InputError);
  CHECK(cursor.remaining() == 1);
  CHECK(std::isinf(io::TextCursor("big.msh", "1e999").real("x")));  // the I/O core rejects it later
  CHECK(io::quoted(std::string(50, '\x01')) == "'" + std::string(40, '?') + "...'");
}

TEST_CASE("names become UTF-8: kept where they are, read as Windows-1252 where not", "[io][utf8]") {
  CHECK(io::as_utf8("plain name") == "plain name");
  CHECK(io::as_utf8("caf\xC3\xA9") == "caf\xC3\xA9");  // already UTF-8
  CHECK(io::as_utf8("caf\xE9") == "caf\xC3\xA9");      // Latin-1 e acute
  CHECK(io::as_utf8("\xE9"
                    "k") ==
        "\xC3\xA9"
        "k");                                                    // a lead byte followed by 0x6B
  CHECK(io::as_utf8("\x80\x99") == "\xE2\x82\xAC\xE2\x84\xA2");  // Windows-1252 euro and trade mark
  CHECK(io::as_utf8("\x81") == "\xC2\x81");                      // unassigned in Windows-1252: the C1 control
  CHECK(io::as_utf8("\xC0\xAF") == "\xC3\x80\xC2\xAF");          // an overlong '/' is not UTF-8
  CHECK(io::as_utf8("\xED\xA0\x80") == "\xC3\xAD\xC2\xA0\xE2\x82\xAC");  // nor is a surrogate
  CHECK(io::as_utf8("\xF0\x9F\x99\x82 \xF0\x9F") ==
        "\xF0\x9F\x99\x82 \xC3\xB0\xC5\xB8");  // a cut 4-byte sequence
  std::string every_byte;
  for (int b = 1; b < 256; ++b) every_byte.push_back(static_cast<char>(b));
  CHECK_FALSE(io::is_utf8(every_byte));
  CHECK(io::is_utf8(io::as_utf8(every_byte)));
  CHECK(io::as_utf8(io::as_utf8(every_byte)) == io::as_utf8(every_byte));
}

TEST_CASE("a library's exception in a reader or writer becomes an error naming the file", "[io]") {
  io::Registry registry;
  io::Format lib;
  lib.name = "lib";
  lib.extensions = {".lib"};
  lib.read_surface = [](const std::filesystem::path&, const io::ReadOptions&) -> TriangleSoup {
    throw std::out_of_range("[json.exception.out_of_range.401] array index 3 is out of range");
  };
  lib.write_surface = [](const TriangleSoup& soup, const std::filesystem::path& path,
                         const io::WriteOptions&) {
    std::ofstream(path) << "partial";
    if (soup.num_vertices() == 3) throw std::bad_alloc();
    throw std::runtime_error("[json.exception.type_error.316] invalid UTF-8 byte at index 9: 0x6B");
  };
  registry.add(lib);
  test::TempDir dir("io_library_errors");
  test::write_text(dir / "in.lib", "x");
  CHECK_THROWS_AS(io::read_surface(registry, dir / "in.lib"), InputError);
  CHECK_THROWS_WITH(io::read_surface(registry, dir / "in.lib"),
                    (dir / "in.lib").string() + ": cannot be read as lib: array index 3 is out of range");
  const TriangleSoup cube = test::cube_soup();
  CHECK_THROWS_AS(io::write_surface(registry, cube, dir / "out.lib"), RunError);
  CHECK_THROWS_WITH(
      io::write_surface(registry, cube, dir / "out.lib"),
      "cannot write " + (dir / "out.lib").string() + " as lib: invalid UTF-8 byte at index 9: 0x6B");
  TriangleSoup triangle;
  triangle.positions = {Vec3d(0, 0, 0), Vec3d(1, 0, 0), Vec3d(0, 1, 0)};
  triangle.triangles = {{0, 1, 2}};
  CHECK_THROWS_WITH(io::write_surface(registry, triangle, dir / "out.lib"), Catch::Contains("out of memory"));
  CHECK(dir.files() == std::vector<std::string>{"in.lib"});  // no output, no temporary file
}
