#include "vdb_tree_walk.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <vector>

namespace mr::plugins::vdb {
namespace {

// The grid's compression flags (io/Compression.h).
constexpr std::uint32_t kZip = 0x1, kActiveMask = 0x2, kBlosc = 0x4;

// Value masks of the nodes of a 5-4-3 tree: a bit per value.
constexpr std::size_t kLeafMaskBytes = 512 / 8;       // LeafNode: 8^3 values
constexpr std::size_t kLowerMaskBytes = 4096 / 8;     // InternalNode 4: 16^3
constexpr std::size_t kUpperMaskBytes = 32768 / 8;    // InternalNode 5: 32^3
constexpr std::int32_t kUpperNodeSide = 8 * 16 * 32;  // voxels across an InternalNode 5
// Origin, child and value masks, and the values' flag byte (when none follow).
constexpr std::size_t kMinUpperNodeBytes = 3 * sizeof(std::int32_t) + 2 * kUpperMaskBytes + 1;

// The flag byte before a node's values (io::readCompressedValues): which
// inactive values follow, and whether a mask selects between them.
enum ValuesFlag : std::int8_t {
  kNoMaskOrInactiveVals,
  kNoMaskAndMinusBg,
  kNoMaskAndOneInactiveVal,
  kMaskAndNoInactiveVals,
  kMaskAndOneInactiveVal,
  kMaskAndTwoInactiveVals,
  kNoMaskAndAllVals
};

std::uint64_t count_on(std::string_view mask) {
  std::uint64_t on = 0;
  for (std::size_t i = 0; i + sizeof(std::uint64_t) <= mask.size(); i += sizeof(std::uint64_t)) {
    std::uint64_t word;
    std::memcpy(&word, mask.data() + i, sizeof word);
    on += static_cast<std::uint64_t>(std::popcount(word));
  }
  return on;
}

std::string text(std::string_view what) { return std::string(what); }

// io::readData (through HalfReader for half floats): `count` values, raw
// or, in a compressed grid, as an int64 length and a zip or Blosc chunk of
// that many bytes; a length <= 0 announces minus that many raw bytes.
void walk_value_data(ByteWalker& in, const TreeValues& values, std::uint64_t count, std::string_view what) {
  if (values.half && count == 0) return;  // HalfReader reads nothing then
  const std::uint64_t expected = count * values.stored_bytes;
  if (!(values.compression & (kBlosc | kZip))) {
    in.take(expected, what);
    return;
  }
  const auto stated = in.number<std::int64_t>(what);
  if (stated <= 0) {
    const std::uint64_t raw = 0 - static_cast<std::uint64_t>(stated);  // no overflow at INT64_MIN
    if (raw != expected)
      in.corrupt(text(what) + " are stated as " + std::to_string(raw) + " raw bytes where the node holds " +
                 std::to_string(expected));
    in.take(expected, what);
    return;
  }
  if (static_cast<std::uint64_t>(stated) > in.left())
    in.corrupt(text(what) + " claim a compressed chunk of " + std::to_string(stated) + " bytes where " +
               std::to_string(in.left()) + " remain");
  const std::string_view chunk = in.take(static_cast<std::size_t>(stated), what);
  if (!(values.compression & kBlosc)) return;  // zlib is told the chunk's length
  const BloscSizes sizes = blosc_header(in, chunk, what);
  if (sizes.uncompressed != expected)
    in.corrupt(text(what) + " are a Blosc chunk of " + std::to_string(sizes.uncompressed) +
               " bytes uncompressed where the node holds " + std::to_string(expected));
}

// io::readCompressedValues for a node whose value mask is `value_mask`: the
// flag byte, up to two inactive values, a selection mask, then only the
// active values if the grid is mask-compressed and the flag allows it, else
// all of them.
void walk_node_values(ByteWalker& in, const TreeValues& values, std::string_view value_mask,
                      std::string_view what) {
  const auto flag = in.number<std::int8_t>(what);
  if (flag < kNoMaskOrInactiveVals || flag > kNoMaskAndAllVals)
    in.corrupt(text(what) + " carry an unknown compression flag " + std::to_string(flag));
  if (flag == kNoMaskAndOneInactiveVal || flag == kMaskAndOneInactiveVal) in.take(values.value_bytes, what);
  if (flag == kMaskAndTwoInactiveVals) in.take(2 * values.value_bytes, what);
  if (flag == kMaskAndNoInactiveVals || flag == kMaskAndOneInactiveVal || flag == kMaskAndTwoInactiveVals)
    in.take(value_mask.size(), what);  // the selection mask
  const bool active_only = (values.compression & kActiveMask) && flag != kNoMaskAndAllVals;
  walk_value_data(in, values, active_only ? count_on(value_mask) : value_mask.size() * 8, what);
}

// InternalNode::readTopology: child mask, value mask, values, then the
// children in child-mask order; a leaf's topology is its value mask.
// Returns the leaves below the node.
std::uint64_t walk_internal_topology(ByteWalker& in, const TreeValues& values, std::size_t mask_bytes) {
  const std::string_view child_mask = in.take(mask_bytes, "internal node masks");
  const std::string_view value_mask = in.take(mask_bytes, "internal node masks");
  walk_node_values(in, values, value_mask, "internal node values");
  const std::uint64_t children = count_on(child_mask);
  if (mask_bytes == kLowerMaskBytes) {
    in.take(children * kLeafMaskBytes, "leaf value masks");
    return children;
  }
  std::uint64_t leaves = 0;
  for (std::uint64_t i = 0; i < children; ++i) leaves += walk_internal_topology(in, values, kLowerMaskBytes);
  return leaves;
}

struct RootKey {
  std::int32_t x, y, z;
  auto operator<=>(const RootKey&) const = default;
};

// A root tile's or child's origin. OpenVDB keys its table by the origin as
// read; a key that no node could have is not written by OpenVDB.
RootKey walk_root_key(ByteWalker& in, std::string_view what) {
  const auto x = in.number<std::int32_t>(what);
  const auto y = in.number<std::int32_t>(what);
  const auto z = in.number<std::int32_t>(what);
  if (x % kUpperNodeSide != 0 || y % kUpperNodeSide != 0 || z % kUpperNodeSide != 0)
    in.corrupt("the root node holds " + text(what) + " at (" + std::to_string(x) + ", " + std::to_string(y) +
               ", " + std::to_string(z) + "), not the origin of a node");
  return {x, y, z};
}

// A second child at the same origin replaces the first in OpenVDB's table
// (which leaks it), and its buffers would no longer be read.
void refuse_repeated_keys(ByteWalker& in, std::vector<RootKey>& keys) {
  std::sort(keys.begin(), keys.end());
  const auto repeated = std::adjacent_find(keys.begin(), keys.end());
  if (repeated != keys.end())
    in.corrupt("the root node holds two nodes or tiles at (" + std::to_string(repeated->x) + ", " +
               std::to_string(repeated->y) + ", " + std::to_string(repeated->z) + ")");
}

void walk_root_tiles(ByteWalker& in, const TreeValues& values, std::uint32_t tiles,
                     std::vector<RootKey>& keys) {
  const std::size_t tile_bytes = 3 * sizeof(std::int32_t) + values.value_bytes + 1;
  if (tiles > in.left() / tile_bytes)
    in.corrupt("the root node claims " + std::to_string(tiles) + " tiles of " + std::to_string(tile_bytes) +
               " bytes where " + std::to_string(in.left()) + " bytes remain");
  for (std::uint32_t i = 0; i < tiles; ++i) {
    keys.push_back(walk_root_key(in, "a tile"));
    in.take(values.value_bytes, "root tiles");
    const auto active = in.number<std::uint8_t>("root tiles");
    if (active > 1) in.corrupt("a root tile's active flag is " + std::to_string(active) + ", not 0 or 1");
  }
}

std::uint64_t walk_root_children(ByteWalker& in, const TreeValues& values, std::uint32_t children,
                                 std::vector<RootKey>& keys) {
  if (children > in.left() / kMinUpperNodeBytes)
    in.corrupt("the root node claims " + std::to_string(children) + " children of at least " +
               std::to_string(kMinUpperNodeBytes) + " bytes where " + std::to_string(in.left()) +
               " bytes remain");
  std::uint64_t leaves = 0;
  for (std::uint32_t i = 0; i < children; ++i) {
    keys.push_back(walk_root_key(in, "a child"));
    leaves += walk_internal_topology(in, values, kUpperMaskBytes);
  }
  return leaves;
}

// RootNode::readTopology: background, tile and child counts, the tiles
// (origin, value, active flag), the children (origin, topology).
std::uint64_t walk_root_topology(ByteWalker& in, const TreeValues& values) {
  in.take(values.value_bytes, "background value");
  const auto tiles = in.number<std::uint32_t>("root tile count");
  const auto children = in.number<std::uint32_t>("root child count");
  std::vector<RootKey> keys;
  walk_root_tiles(in, values, tiles, keys);
  const std::uint64_t leaves = walk_root_children(in, values, children, keys);
  refuse_repeated_keys(in, keys);
  return leaves;
}

}  // namespace

std::optional<TreeValues> walked_tree_values(std::string_view tree_type, bool half) {
  struct Walked {
    std::string_view type;
    std::size_t value_bytes;
    std::size_t half_bytes;  // 0: not a real type (io::RealToHalf), saved in full even in a half grid
  };
  static constexpr Walked kWalked[] = {{"Tree_float_5_4_3", 4, 2},  {"Tree_double_5_4_3", 8, 2},
                                       {"Tree_int32_5_4_3", 4, 0},  {"Tree_int64_5_4_3", 8, 0},
                                       {"Tree_vec3s_5_4_3", 12, 6}, {"Tree_vec3d_5_4_3", 24, 6},
                                       {"Tree_vec3i_5_4_3", 12, 0}};
  for (const Walked& walked : kWalked) {
    if (walked.type != tree_type) continue;
    TreeValues values;
    values.value_bytes = walked.value_bytes;
    values.half = half && walked.half_bytes != 0;
    values.stored_bytes = values.half ? walked.half_bytes : walked.value_bytes;
    return values;
  }
  return std::nullopt;
}

WalkedTree walk_tree(ByteWalker& in, const TreeValues& values) {
  in.take(sizeof(std::int32_t), "tree buffer count");  // TreeBase::readTopology: any count reads the same
  WalkedTree tree;
  tree.leaves = walk_root_topology(in, values);
  tree.buffers_at = in.at();
  // Tree::readBuffers: per leaf its value mask (read again) and values. (It
  // visits the root's children by origin, not as read; all leaves read alike.)
  for (std::uint64_t i = 0; i < tree.leaves; ++i) {
    const std::string_view value_mask = in.take(kLeafMaskBytes, "leaf value masks");
    walk_node_values(in, values, value_mask, "leaf values");
  }
  return tree;
}

}  // namespace mr::plugins::vdb
