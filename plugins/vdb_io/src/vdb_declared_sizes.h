#pragma once
// OpenVDB (10) reads a name or a metadata value by allocating the length
// the file states, then reading: a 300-byte file claiming a 4 GB grid name
// made it fill 4 GB and take 9 s before failing. The headers before the
// first grid's tree (file header, file metadata, grid descriptors, grid
// metadata, transform name) are walked here first, and a stated length
// longer than the bytes left is refused.

#include <string>
#include <string_view>

namespace mr::plugins::vdb {

/// Throws InputError naming `source` if a length in the headers of the
/// VDB file `bytes` runs past its end. Files of other format versions than
/// the ones walked (222 to 224: OpenVDB 3 to 10) and layouts it does not
/// follow are left to OpenVDB.
void check_vdb_declared_sizes(std::string_view bytes, const std::string& source);

}  // namespace mr::plugins::vdb
