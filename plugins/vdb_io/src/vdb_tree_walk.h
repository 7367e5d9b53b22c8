#pragma once
// A grid's tree, walked as OpenVDB 10 reads it from a stream (Tree::
// readTopology, then Tree::readBuffers), for the trees of the standard
// configuration (RootNode, InternalNode 5, InternalNode 4, LeafNode 3) of
// float, double, int32, int64, vec3s, vec3d and vec3i values.
//
// OpenVDB trusts the sizes a tree states: a raw value buffer is read with
// the length the file gives (io::bloscFromStream, io::unzipFromStream: a
// heap overflow when it exceeds the node's buffer), a compressed one is
// allocated at its stated length before being read, and the root's tile
// and child counts are not bounded. The walk refuses what does not fit.

#include "vdb_byte_walker.h"

#include <cstdint>
#include <optional>
#include <string_view>

namespace mr::plugins::vdb {

/// How one tree stores its values.
struct TreeValues {
  std::size_t value_bytes = 0;    ///< sizeof(ValueType): background, tiles, inactive values
  std::size_t stored_bytes = 0;   ///< bytes of one value in a node's value buffer
  bool half = false;              ///< buffers hold half floats ("_HalfFloat" grids of real values)
  std::uint32_t compression = 0;  ///< the grid's flags (io::COMPRESS_ZIP, _ACTIVE_MASK, _BLOSC)
};

/// The values of a tree of type `tree_type` ("Tree_float_5_4_3", the grid
/// type without its "_HalfFloat" suffix, which `half` says it had), with no
/// compression, or nullopt for the types not walked.
std::optional<TreeValues> walked_tree_values(std::string_view tree_type, bool half);

struct WalkedTree {
  std::uint64_t leaves = 0;
  std::size_t buffers_at = 0;  ///< where the leaves' buffers begin in the file
};

/// Walks a tree from `in`'s position to its end.
/// Refuses (InputError) a raw value buffer whose stated length differs from
/// the node's; a compressed one longer than the bytes left, or a Blosc one
/// whose header does not match; tile and child counts the bytes left cannot
/// hold; an unknown value-compression flag; a tile's active flag other than
/// 0 or 1; a root key that is not a child node's origin or appears twice
/// (OpenVDB would leak the first child).
WalkedTree walk_tree(ByteWalker& in, const TreeValues& values);

}  // namespace mr::plugins::vdb
