#pragma once
// OpenVDB (10) trusts the sizes a file states. It reads a name or a
// metadata value by allocating the length the file gives, then reading (a
// 300-byte file claiming a 4 GB grid name made it fill 4 GB); it reads a raw
// value buffer with the length the file gives, into a node's fixed-size
// buffer (a heap overflow); it allocates a compressed buffer at its stated
// length before reading it. So before OpenVDB reads a file, the whole of it
// is walked here as io::Stream reads it (file header and metadata, then per
// grid its descriptor, compression flags, metadata, transform and tree: see
// vdb_metadata_walk.h and vdb_tree_walk.h), and a stated size that does not
// fit is refused.
//
// Only trees of float, double, int32, int64 and vec3 (s, d, i) values in the
// standard configuration are walked; a file with a grid of any other type
// (bool, mask, points, other node sizes) is refused, naming the grid: our
// readers only ever use float grids.
//
// Format versions: 222 to 224 (OpenVDB 3 to 10) are walked. OpenVDB 10 reads
// a later version as if it were 224, after a warning, so such files are
// walked the same way. Earlier versions (OpenVDB 2 and before) are refused:
// OpenVDB 10 still reads them, through the same trusting code, in layouts
// this walk does not follow, so leaving them to it would leave the holes
// open. A file that does not start with the VDB magic number is left to
// OpenVDB, which refuses it before reading anything else.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mr::plugins::vdb {

/// What the walk found of one grid.
struct WalkedGrid {
  std::string name;
  std::string type;            ///< as stated, with any "_HalfFloat" suffix
  bool instance = false;       ///< shares another grid's tree, so has none of its own
  std::size_t tree_at = 0;     ///< where its tree begins in the file (0 for an instance)
  std::size_t buffers_at = 0;  ///< where its leaves' buffers begin (0 for an instance)
  std::uint64_t leaves = 0;
};

struct VdbWalk {
  bool walked = false;  ///< false: not a VDB file, left to OpenVDB
  std::vector<WalkedGrid> grids;
  std::size_t end = 0;  ///< where OpenVDB stops reading
};

/// Walks the VDB file `bytes` as OpenVDB 10 reads it; throws InputError
/// naming `source` at the first stated size that does not fit, at a grid
/// of a type not walked, and where the file ends early.
VdbWalk walk_vdb_file(std::string_view bytes, const std::string& source);

/// walk_vdb_file, for its refusals only.
void check_vdb_declared_sizes(std::string_view bytes, const std::string& source);

}  // namespace mr::plugins::vdb
