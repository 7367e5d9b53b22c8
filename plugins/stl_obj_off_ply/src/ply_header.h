#pragma once
// The header of a PLY file: encoding, elements with their counts and typed
// properties, and the region names this plugin stores in comments.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mr::plugins::stl_obj_off_ply {

enum class PlyType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };
enum class PlyEncoding { ascii, binary_little_endian, binary_big_endian };

std::size_t ply_type_size(PlyType type);
bool ply_type_is_integer(PlyType type);
const char* ply_type_name(PlyType type);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::float32;  ///< the item type of a list
  bool is_list = false;
  PlyType count_type = PlyType::uint8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;

  /// The fewest bytes one entry can take in a binary body (lists empty).
  std::uint64_t min_binary_size() const;
  /// Index of the property named `name`, or -1.
  int find(std::string_view name) const;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::ascii;
  std::vector<PlyElement> elements;
  /// From "comment region <id> <name>" lines, indexed by id.
  std::vector<std::string> region_names;
  std::size_t body_offset = 0;  ///< byte offset just past "end_header\n"
};

/// Parses the header; throws InputError naming `path` on anything malformed.
PlyHeader parse_ply_header(const std::string& path, std::string_view bytes);

}  // namespace mr::plugins::stl_obj_off_ply
