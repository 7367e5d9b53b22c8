#include "ply_header.h"

#include <mr/io/text_cursor.h>

#include <array>
#include <utility>

namespace mr::plugins::stl_obj_off_ply {
namespace {

constexpr std::array<std::pair<const char*, PlyType>, 16> kTypeNames{{
    {"char", PlyType::int8},
    {"int8", PlyType::int8},
    {"uchar", PlyType::uint8},
    {"uint8", PlyType::uint8},
    {"short", PlyType::int16},
    {"int16", PlyType::int16},
    {"ushort", PlyType::uint16},
    {"uint16", PlyType::uint16},
    {"int", PlyType::int32},
    {"int32", PlyType::int32},
    {"uint", PlyType::uint32},
    {"uint32", PlyType::uint32},
    {"float", PlyType::float32},
    {"float32", PlyType::float32},
    {"double", PlyType::float64},
    {"float64", PlyType::float64},
}};

constexpr std::size_t kMaxRegionId = 1 << 20;

PlyType parse_type(const io::TextCursor& cursor, std::string_view name) {
  for (const auto& [text, type] : kTypeNames)
    if (name == text) return type;
  cursor.fail("unknown PLY property type '" + std::string(name) + "'");
}

PlyEncoding parse_format(const io::TextCursor& cursor, io::Tokens& tokens) {
  const std::string_view format = tokens.next();
  if (format == "ascii") return PlyEncoding::ascii;
  if (format == "binary_little_endian") return PlyEncoding::binary_little_endian;
  if (format == "binary_big_endian") return PlyEncoding::binary_big_endian;
  cursor.fail("unknown PLY format '" + std::string(format) + "'");
}

PlyProperty parse_property(const io::TextCursor& cursor, io::Tokens& tokens) {
  PlyProperty property;
  std::string_view type = tokens.next();
  if (type == "list") {
    property.is_list = true;
    property.count_type = parse_type(cursor, tokens.next());
    if (!ply_type_is_integer(property.count_type)) cursor.fail("a list count must have an integer type");
    type = tokens.next();
  }
  property.type = parse_type(cursor, type);
  property.name = std::string(tokens.next());
  if (property.name.empty()) cursor.fail("property without a name");
  return property;
}

void parse_region_comment(const io::TextCursor& cursor, io::Tokens& tokens, PlyHeader& header) {
  if (tokens.next() != "region") return;
  std::int64_t id = 0;
  if (!io::parse_integer(tokens.next(), id) || id < 0) return;
  if (static_cast<std::size_t>(id) >= kMaxRegionId)
    cursor.fail("region id " + std::to_string(id) + " too large");
  if (header.region_names.size() <= static_cast<std::size_t>(id)) header.region_names.resize(id + 1);
  header.region_names[id] = std::string(io::trim(tokens.rest()));
}

}  // namespace

std::size_t ply_type_size(PlyType type) {
  switch (type) {
    case PlyType::int8:
    case PlyType::uint8:
      return 1;
    case PlyType::int16:
    case PlyType::uint16:
      return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32:
      return 4;
    case PlyType::float64:
      return 8;
  }
  return 0;
}

bool ply_type_is_integer(PlyType type) { return type != PlyType::float32 && type != PlyType::float64; }

const char* ply_type_name(PlyType type) {
  for (const auto& [text, t] : kTypeNames)
    if (t == type) return text;
  return "?";
}

std::uint64_t PlyElement::min_binary_size() const {
  std::uint64_t size = 0;
  for (const PlyProperty& p : properties) size += ply_type_size(p.is_list ? p.count_type : p.type);
  return size;
}

int PlyElement::find(std::string_view wanted) const {
  for (std::size_t i = 0; i < properties.size(); ++i)
    if (properties[i].name == wanted) return static_cast<int>(i);
  return -1;
}

PlyHeader parse_ply_header(const std::string& path, std::string_view bytes) {
  io::TextCursor cursor(path, bytes);
  std::string_view line;
  if (!cursor.next_line(line) || io::trim(line) != "ply")
    throw InputError(path, "not a PLY file: it does not start with 'ply'");
  PlyHeader header;
  bool has_format = false;
  while (cursor.next_line(line)) {
    io::Tokens tokens(line);
    const std::string_view keyword = tokens.next();
    if (keyword == "end_header") {
      if (!has_format) cursor.fail("no 'format' line in the PLY header");
      header.body_offset = cursor.position();
      return header;
    }
    if (keyword == "format") {
      header.encoding = parse_format(cursor, tokens);
      has_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      element.name = std::string(tokens.next());
      std::int64_t count = 0;
      if (!io::parse_integer(tokens.next(), count) || count < 0)
        cursor.fail("bad count for element '" + element.name + "'");
      element.count = static_cast<std::uint64_t>(count);
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) cursor.fail("property before any element");
      header.elements.back().properties.push_back(parse_property(cursor, tokens));
    } else if (keyword == "comment") {
      parse_region_comment(cursor, tokens, header);
    } else if (!keyword.empty() && keyword != "obj_info") {
      cursor.fail("unknown PLY header line '" + std::string(line.substr(0, 60)) + "'");
    }
  }
  throw InputError(path, "the PLY header has no 'end_header'");
}

}  // namespace mr::plugins::stl_obj_off_ply
