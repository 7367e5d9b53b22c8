#pragma once
// A Draco file states its element counts before its data, and the decoder
// allocates for them up front: a 73-byte file claiming 16 million faces made
// it take 15 GB and 25 s before failing. The counts are read here first and
// checked against the file's size.

#include <string>
#include <string_view>

namespace mr::plugins::detail {

/// Most elements (faces or points) one byte of a valid Draco mesh can hold.
/// A perfectly regular grid, the most compressible mesh there is, holds 11
/// faces per byte with our encoder's settings; this leaves a margin of 20.
inline constexpr double kMaxDracoElementsPerByte = 256.0;

/// Throws InputError naming `source` if the mesh `bytes` start with claims
/// more faces or points than kMaxDracoElementsPerByte allows for its size.
/// Files it cannot parse are left to the decoder, which rejects them.
void check_draco_declared_sizes(std::string_view bytes, const std::string& source);

}  // namespace mr::plugins::detail
