#include "test_support.h"

#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

using namespace mr;

namespace {

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("every writer gives the same bytes for the same mesh", "[io][determinism][slow]") {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("determinism");
  TriangleSoup soup = test::cube_soup();
  soup.face_regions = {0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1};
  std::size_t compared = 0;
  for (const io::Format& format : registry.formats()) {
    if (!format.can_write()) continue;
    for (bool binary : {true, false}) {
      const std::string ext = format.extensions.front();
      io::WriteOptions options;
      options.binary = binary;
      const auto first = dir / ("a" + ext), second = dir / ("b" + ext);
      if (format.write_surface) {
        io::write_surface(registry, soup, first, options);
        io::write_surface(registry, soup, second, options);
      } else {
        io::write_volume(registry, test::cube_tets(), first, options);
        io::write_volume(registry, test::cube_tets(), second, options);
      }
      INFO(format.name << (binary ? " binary" : " ascii"));
      CHECK(file_bytes(first) == file_bytes(second));
      CHECK(!file_bytes(first).empty());
      ++compared;
    }
  }
  CHECK(compared >= 2 * 10);
}
