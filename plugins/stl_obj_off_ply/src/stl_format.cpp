// STL reader. Our own rather than OpenMesh's STLReader: OpenMesh reads
// through an istream into a halfedge-oriented importer, welds through a
// std::map (slow on millions of facets), reports problems on its global omerr
// stream instead of failing, and trusts the binary facet count. Here the whole
// file is in memory, the binary count is checked against the file size before
// anything is allocated, and corners are welded by a hash on the exact bits.
//
// Binary or ASCII: a file is binary when 84 + 50 n equals its size (n = the
// count at byte 80), even if its header starts with "solid"; ASCII when it
// starts with "solid" and holds only text; binary otherwise.

#include "formats.h"
#include "soup_importer.h"

#include <mr/io/file_bytes.h>
#include <mr/io/text_cursor.h>

#include <algorithm>
#include <cmath>

namespace mr::plugins::stl_obj_off_ply {
namespace {

constexpr std::size_t kHeaderSize = 80;
constexpr std::size_t kFacetSize = 50;

std::uint64_t binary_facet_count(std::string_view bytes) {
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + kHeaderSize, sizeof(count));
  return count;
}

bool looks_like_ascii(std::string_view text) {
  const std::size_t start = text.find_first_not_of(" \t\r\n");
  if (start == std::string_view::npos || !io::istarts_with(text.substr(start), "solid")) return false;
  const std::string_view sample = text.substr(0, 1024);
  return std::none_of(sample.begin(), sample.end(),
                      [](char c) { return static_cast<unsigned char>(c) < 9 || c == 127; });
}

TriangleSoup read_binary_stl(const std::string& path, std::string_view bytes) {
  io::ByteReader reader(path, bytes.data(), bytes.size());
  reader.skip(kHeaderSize, "the 80-byte header");
  const std::uint32_t count = reader.read<std::uint32_t>("the facet count");
  if (static_cast<std::uint64_t>(count) > reader.remaining() / kFacetSize)
    reader.fail("the binary STL header claims " + std::to_string(count) + " facets (" +
                std::to_string(kHeaderSize + 4 + std::uint64_t{count} * kFacetSize) +
                " bytes) but the file has only " + std::to_string(bytes.size()) + " bytes");
  return weld_float_corners(bytes.data() + reader.position(), count, kFacetSize, 12);  // after the normal
}

// Parses "solid ... endsolid" blocks; a polygon loop of more than 3 vertices is fanned.
class AsciiStlParser {
 public:
  AsciiStlParser(const std::string& path, std::string_view text) : cursor_(path, text) {}

  TriangleSoup parse() {
    std::string_view line;
    while (cursor_.next_content_line(line, '\0')) {
      io::Tokens tokens(line);
      const std::string_view keyword = tokens.next();
      if (!io::iequals(keyword, "solid"))
        cursor_.fail("expected 'solid', found '" + std::string(keyword) + "'");
      parse_solid(std::string(io::trim(tokens.rest())));
    }
    if (solids_ == 0) cursor_.fail("no 'solid' in the file");
    TriangleSoup soup = weld_triangle_corners(corners_);
    if (regions_.names().size() > 1) {
      soup.face_regions = std::move(face_regions_);
      soup.region_names = regions_.names();
    }
    return soup;
  }

 private:
  void parse_solid(const std::string& name) {
    ++solids_;
    const std::int32_t region = regions_.id_of(name);
    std::string_view line;
    while (cursor_.next_content_line(line, '\0')) {
      io::Tokens tokens(line);
      const std::string_view keyword = tokens.next();
      if (io::iequals(keyword, "endsolid")) return;
      if (!io::iequals(keyword, "facet"))
        cursor_.fail("expected 'facet' or 'endsolid', found '" + std::string(keyword) + "'");
      parse_facet(region);
    }
    cursor_.fail("the file ends inside a solid (no 'endsolid')");
  }

  void parse_facet(std::int32_t region) {
    expect_line("outer", "loop");
    loop_.clear();
    std::string_view line;
    while (cursor_.next_content_line(line, '\0')) {
      io::Tokens tokens(line);
      const std::string_view keyword = tokens.next();
      if (io::iequals(keyword, "endloop")) break;
      if (!io::iequals(keyword, "vertex"))
        cursor_.fail("expected 'vertex' or 'endloop', found '" + std::string(keyword) + "'");
      Vec3f p;
      for (int k = 0; k < 3; ++k) p[k] = coordinate(tokens.next());
      loop_.push_back(p.cast<double>());
    }
    if (loop_.size() < 3)
      cursor_.fail("facet with " + std::to_string(loop_.size()) + " vertices, needs at least 3");
    expect_line("endfacet", {});
    for (std::size_t i = 1; i + 1 < loop_.size(); ++i) {
      corners_.insert(corners_.end(), {loop_[0], loop_[i], loop_[i + 1]});
      face_regions_.push_back(region);
    }
  }

  // STL stores float32, so text coordinates are read as float: an ASCII file
  // then reads exactly like the binary file with the same numbers.
  float coordinate(std::string_view token) const {
    float value = 0;
    if (token.empty()) cursor_.fail("missing vertex coordinate");
    if (!io::parse_number(token, value))
      cursor_.fail(io::quoted(token) + " is not a number (vertex coordinate)");
    if (!std::isfinite(value))
      cursor_.fail("vertex coordinate is not finite (NaN, Inf or beyond float range)");
    return value;
  }

  void expect_line(std::string_view first, std::string_view second) {
    std::string_view line;
    if (!cursor_.next_content_line(line, '\0')) cursor_.fail("the file ends inside a facet");
    io::Tokens tokens(line);
    if (!io::iequals(tokens.next(), first) || (!second.empty() && !io::iequals(tokens.next(), second)))
      cursor_.fail("expected '" + std::string(first) + (second.empty() ? "" : " ") + std::string(second) +
                   "', found '" + std::string(line.substr(0, 60)) + "'");
  }

  io::TextCursor cursor_;
  std::vector<Vec3d> corners_;
  std::vector<Vec3d> loop_;
  std::vector<std::int32_t> face_regions_;
  RegionTable regions_;
  int solids_ = 0;
};

}  // namespace

TriangleSoup read_stl(std::string_view bytes, const std::string& name) {
  const bool exact_binary_size = bytes.size() >= kHeaderSize + 4 &&
                                 kHeaderSize + 4 + binary_facet_count(bytes) * kFacetSize == bytes.size();
  if (!exact_binary_size && looks_like_ascii(bytes)) return AsciiStlParser(name, bytes).parse();
  if (bytes.size() < kHeaderSize + 4)
    throw InputError(name, "too short for a binary STL (" + std::to_string(bytes.size()) +
                               " bytes, the header alone is 84) and not an ASCII STL");
  return read_binary_stl(name, bytes);
}

}  // namespace mr::plugins::stl_obj_off_ply
