#include "vdb_declared_sizes.h"

#include "vdb_byte_walker.h"
#include "vdb_metadata_walk.h"
#include "vdb_tree_walk.h"

#include <optional>

namespace mr::plugins::vdb {
namespace {

constexpr std::int64_t kMagic = 0x56444220;  // " BDV"
constexpr std::uint32_t kFirstWalkedVersion = 222;
constexpr std::size_t kLibraryVersionBytes = 8;  // two uint32
constexpr std::size_t kUuidCharacters = 36;
constexpr std::string_view kHalfSuffix = "_HalfFloat";
// A grid descriptor (three name lengths, three offsets), compression flags,
// a metadata count and a transform type length.
constexpr std::size_t kMinGridBytes = 3 * 4 + 3 * 8 + 4 + 4 + 4;

bool is_space(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }
bool is_hex_digit(char c) {
  return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

// Archive::readHeader reads the UUID with boost's operator>>: 36 characters,
// hex digits with dashes after the 8th, 12th, 16th and 20th, each read as
// formatted input, which skips whitespace before it.
void walk_uuid(ByteWalker& in) {
  for (std::size_t i = 0; i < kUuidCharacters; ++i) {
    char c = in.number<char>("file UUID");
    while (is_space(c)) c = in.number<char>("file UUID");
    const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
    if (dash ? c != '-' : !is_hex_digit(c)) in.corrupt("its UUID is not 32 hex digits and 4 dashes");
  }
}

// Bytes of the data of a map (math/Maps.h, each map's read()); 0 for a type
// OpenVDB does not know (it throws before reading on).
std::size_t map_bytes(std::string_view type) {
  struct Map {
    std::string_view type;
    std::size_t bytes;
  };
  static constexpr Map kMaps[] = {{"AffineMap", 128},
                                  {"UnitaryMap", 128},
                                  {"ScaleMap", 5 * 24},
                                  {"UniformScaleMap", 5 * 24},
                                  {"TranslationMap", 24},
                                  {"ScaleTranslateMap", 6 * 24},
                                  {"UniformScaleTranslateMap", 6 * 24}};
  for (const Map& map : kMaps)
    if (map.type == type) return map.bytes;
  return 0;
}

// Transform::read: the map's type name and data. A frustum map's data (a
// bounding box, taper and depth) is followed by a second map, read the same way.
void walk_transform(ByteWalker& in) {
  constexpr std::string_view kFrustum = "NonlinearFrustumMap";
  constexpr std::size_t kFrustumBytes = 2 * 24 + 8 + 8;
  std::string_view type = in.sized("transform type");
  for (; type == kFrustum; type = in.sized("transform type")) in.take(kFrustumBytes, "transform");
  const std::size_t bytes = map_bytes(type);
  if (bytes == 0) in.corrupt("the transform has an unknown map type " + quoted(type));
  in.take(bytes, "transform");
}

// GridDescriptor::read, then Archive::readGrid: compression flags,
// metadata, transform and, unless the grid is an instance of another, its tree.
// io::Stream reads the grids one after the other, not at their offsets.
WalkedGrid walk_grid(ByteWalker& in) {
  WalkedGrid grid;
  grid.name = in.sized("grid name");
  grid.type = in.sized("grid type");
  std::string_view tree_type = grid.type;
  const bool half = tree_type.ends_with(kHalfSuffix);
  if (half) tree_type.remove_suffix(kHalfSuffix.size());
  std::optional<TreeValues> values = walked_tree_values(tree_type, half);
  if (!values)
    in.unsupported("OpenVDB grid " + quoted(grid.name) + " has type " + quoted(grid.type) +
                   ", which is not read: only grids of float, double, int32, int64 or vec3 values in "
                   "OpenVDB's standard tree (5-4-3) are");
  grid.instance = !in.sized("instance parent name").empty();
  in.take(3 * sizeof(std::int64_t), "grid offsets");
  values->compression = in.number<std::uint32_t>("grid compression flags");
  walk_metadata(in);
  walk_transform(in);
  if (grid.instance) return grid;
  grid.tree_at = in.at();
  const WalkedTree tree = walk_tree(in, *values);
  grid.buffers_at = tree.buffers_at;
  grid.leaves = tree.leaves;
  return grid;
}

}  // namespace

VdbWalk walk_vdb_file(std::string_view bytes, const std::string& source) {
  ByteWalker in(bytes, source);
  VdbWalk walk;
  if (in.number<std::int64_t>("file header") != kMagic) return walk;
  walk.walked = true;
  const auto version = in.number<std::uint32_t>("file header");
  if (version < kFirstWalkedVersion)
    in.unsupported("OpenVDB file format version " + std::to_string(version) +
                   " (OpenVDB 2 or older) is not read: only version 222 (OpenVDB 3) and later are");
  in.take(kLibraryVersionBytes + 1, "file header");  // then whether the grids have offsets
  walk_uuid(in);
  walk_metadata(in);
  const auto grids = in.number<std::int32_t>("grid count");
  if (grids < 0 || static_cast<std::size_t>(grids) > in.left() / kMinGridBytes)
    in.corrupt("it claims " + std::to_string(grids) + " grids where " + std::to_string(in.left()) +
               " bytes remain");
  for (std::int32_t g = 0; g < grids; ++g) walk.grids.push_back(walk_grid(in));
  walk.end = in.at();
  return walk;
}

void check_vdb_declared_sizes(std::string_view bytes, const std::string& source) {
  walk_vdb_file(bytes, source);
}

}  // namespace mr::plugins::vdb
