#pragma once
// The GLB container: a 12-byte header, a JSON chunk and an optional BIN chunk.
// split_glb checks every length field against the bytes really present.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mr::plugins::gltf {

/// True if `bytes` start with the GLB magic "glTF".
bool has_glb_magic(std::string_view bytes);

struct GlbChunks {
  std::string_view glb;            ///< the container itself: the file up to the header's length field
  std::string_view json;           ///< the JSON chunk's payload
  std::string_view bin;            ///< the BIN chunk's payload; empty if there is none
  std::size_t json_chunk_end = 0;  ///< offset just past the JSON chunk
};

/// Throws InputError naming `path` on a wrong magic or version, or on any
/// length field that points past the end of the file.
GlbChunks split_glb(std::string_view bytes, const std::string& path);

/// A GLB file holding `json` (padded with spaces) and, if not empty, `bin`
/// (padded with zeros).
std::vector<char> assemble_glb(std::string_view json, std::string_view bin);

/// Replaces the JSON chunk of a checked container, keeping the chunks after it.
std::vector<char> replace_glb_json(const GlbChunks& chunks, std::string_view json);

}  // namespace mr::plugins::gltf
