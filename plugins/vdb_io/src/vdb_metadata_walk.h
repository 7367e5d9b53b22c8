#pragma once
// The metadata of a VDB file and of each grid, walked as OpenVDB 10 reads
// it (MetaMap::readMeta): a count, then per entry a name, a type name and a
// value preceded by its size.

#include "vdb_byte_walker.h"

namespace mr::plugins::vdb {

/// Walks one metadata block from `in`'s position. Refuses a name or value
/// longer than the bytes left; a value of a fixed-size type whose stated
/// size differs from the type's (OpenVDB reads such a value by its type,
/// and would go on out of step); and delayed-load metadata ("__delayedload",
/// which io::File writes for every grid) stating more than its size holds,
/// more entries than the file has leaves, or Blosc chunks that do not fit:
/// OpenVDB allocates its entries from the stated count and decompresses the
/// chunks by their own headers.
void walk_metadata(ByteWalker& in);

}  // namespace mr::plugins::vdb
