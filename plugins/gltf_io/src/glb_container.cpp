#include "glb_container.h"

#include <mr/io/file_bytes.h>

namespace mr::plugins::gltf {
namespace {

constexpr std::uint32_t glb_magic = 0x46546C67;  // "glTF"
constexpr std::uint32_t json_chunk_type = 0x4E4F534A;
constexpr std::uint32_t bin_chunk_type = 0x004E4942;
constexpr std::size_t header_size = 12;
constexpr std::size_t chunk_header_size = 8;

void put_u32(std::vector<char>& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFF));
}

void put_chunk(std::vector<char>& out, std::uint32_t type, std::string_view payload, char pad) {
  const std::size_t padded = (payload.size() + 3) / 4 * 4;
  put_u32(out, static_cast<std::uint32_t>(padded));
  put_u32(out, type);
  out.insert(out.end(), payload.begin(), payload.end());
  out.resize(out.size() + (padded - payload.size()), pad);
}

void set_total_length(std::vector<char>& glb) {
  const auto length = static_cast<std::uint32_t>(glb.size());
  for (int i = 0; i < 4; ++i) glb[8 + i] = static_cast<char>((length >> (8 * i)) & 0xFF);
}

}  // namespace

bool has_glb_magic(std::string_view bytes) { return bytes.size() >= 4 && bytes.substr(0, 4) == "glTF"; }

GlbChunks split_glb(std::string_view bytes, const std::string& path) {
  io::ByteReader in(path, bytes.data(), bytes.size());
  if (in.read<std::uint32_t>("GLB magic") != glb_magic)
    in.fail("not a GLB file: wrong magic (expected \"glTF\")");
  const auto version = in.read<std::uint32_t>("GLB version");
  if (version != 2) in.fail("unsupported GLB version " + std::to_string(version) + " (only 2 is supported)");
  const auto length = in.read<std::uint32_t>("GLB length");
  if (length > bytes.size())
    in.fail("GLB length field says " + std::to_string(length) + " bytes but the file has only " +
            std::to_string(bytes.size()));
  if (length < header_size + chunk_header_size)
    in.fail("GLB length field " + std::to_string(length) + " is too small");

  GlbChunks chunks;
  chunks.glb = bytes.substr(0, length);
  io::ByteReader glb(path, chunks.glb.data(), chunks.glb.size());
  glb.seek(header_size, "GLB header");
  const auto json_length = glb.read<std::uint32_t>("JSON chunk length");
  if (glb.read<std::uint32_t>("JSON chunk type") != json_chunk_type)
    glb.fail("the first GLB chunk is not JSON");
  if (json_length > glb.remaining())
    glb.fail("JSON chunk length " + std::to_string(json_length) + " runs past the end of the GLB (" +
             std::to_string(glb.remaining()) + " bytes left)");
  chunks.json = glb.take(json_length, "JSON chunk");
  chunks.json_chunk_end = glb.position();
  if (glb.remaining() == 0) return chunks;

  const auto bin_length = glb.read<std::uint32_t>("BIN chunk length");
  const auto bin_type = glb.read<std::uint32_t>("BIN chunk type");
  if (bin_length > glb.remaining())
    glb.fail("BIN chunk length " + std::to_string(bin_length) + " runs past the end of the GLB (" +
             std::to_string(glb.remaining()) + " bytes left)");
  if (bin_type == bin_chunk_type) chunks.bin = glb.take(bin_length, "BIN chunk");
  return chunks;
}

std::vector<char> assemble_glb(std::string_view json, std::string_view bin) {
  std::vector<char> out;
  out.reserve(header_size + 2 * chunk_header_size + json.size() + bin.size() + 8);
  put_u32(out, glb_magic);
  put_u32(out, 2);
  put_u32(out, 0);
  put_chunk(out, json_chunk_type, json, ' ');
  if (!bin.empty()) put_chunk(out, bin_chunk_type, bin, '\0');
  set_total_length(out);
  return out;
}

std::vector<char> replace_glb_json(const GlbChunks& chunks, std::string_view json) {
  std::vector<char> out = assemble_glb(json, {});
  const std::string_view rest = chunks.glb.substr(chunks.json_chunk_end);
  out.insert(out.end(), rest.begin(), rest.end());
  set_total_length(out);
  return out;
}

}  // namespace mr::plugins::gltf
