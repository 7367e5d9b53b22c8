#include "test_support.h"

#include <mr/core/errors.h>
#include <mr/io/atomic_file.h>
#include <mr/io/file_bytes.h>
#include <mr/io/mesh_io.h>

#include <catch2/catch.hpp>

#include <fstream>

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
  toy.write_surface = [](const TriangleSoup& soup, const std::filesystem::path& path, const io::WriteOptions&) {
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
