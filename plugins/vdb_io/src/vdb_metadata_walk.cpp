#include "vdb_metadata_walk.h"

#include <cstdint>
#include <limits>

namespace mr::plugins::vdb {
namespace {

constexpr std::string_view kDelayedLoadType = "__delayedload";
// Every leaf takes its 64-byte value mask twice in the file (topology and
// buffers): a file of n bytes holds fewer than n / 128 leaves.
constexpr std::size_t kMinFileBytesPerLeaf = 128;
// OpenVDB pads what it compresses with Blosc to at least this many bytes
// (points/StreamCompression.h, BLOSC_PAD_BYTES).
constexpr std::uint64_t kBloscPadBytes = 128;

// Bytes of a metadata value of OpenVDB's fixed-size types (openvdb.h's
// MetaTypes, and the point index types points::internal::initialize adds
// as int32/int64); 0 for the others (strings, and types it does not know,
// read by their stated size).
std::size_t fixed_size(std::string_view type) {
  struct Known {
    std::string_view type;
    std::size_t bytes;
  };
  static constexpr Known kKnown[] = {{"bool", 1},    {"int32", 4},   {"int64", 8},       {"float", 4},
                                     {"double", 8},  {"vec2i", 8},   {"vec2s", 8},       {"vec2d", 16},
                                     {"vec3i", 12},  {"vec3s", 12},  {"vec3d", 24},      {"vec4i", 16},
                                     {"vec4s", 16},  {"vec4d", 32},  {"mat4s", 64},      {"mat4d", 128},
                                     {"ptidx32", 4}, {"ptidx64", 8}, {"ptdataidx32", 4}, {"ptdataidx64", 8}};
  for (const Known& known : kKnown)
    if (known.type == type) return known.bytes;
  return 0;
}

// One array of DelayedLoadMetadata::readValue: a uint32 byte count, then
// `count` entries, raw when the byte count is 0, else a Blosc chunk of that
// many bytes. The array of compressed sizes may be absent (count UINT32_MAX).
void walk_delayed_load_array(ByteWalker& value, std::uint32_t count, std::size_t entry_bytes,
                             const std::string& what, bool may_be_absent) {
  const auto chunk_bytes = value.number<std::uint32_t>(what);
  if (may_be_absent && chunk_bytes == std::numeric_limits<std::uint32_t>::max()) return;
  const std::uint64_t expected = std::uint64_t{count} * entry_bytes;
  if (chunk_bytes == 0) {
    value.take(expected, what);
    return;
  }
  const BloscSizes sizes = blosc_header(value, value.take(chunk_bytes, what), what);
  if (sizes.uncompressed != expected && !(sizes.uncompressed == kBloscPadBytes && expected <= kBloscPadBytes))
    value.corrupt(what + " decompress to " + std::to_string(sizes.uncompressed) + " bytes, not the " +
                  std::to_string(expected) + " of " + std::to_string(count) + " entries");
}

// DelayedLoadMetadata::readValue reads a leaf count, a byte per leaf and an
// int64 per leaf, allocating them from the count, whatever the value's
// stated size; it then skips what is left of that size. Written by
// OpenVDB, the arrays fill the stated size exactly; here they must fit in it.
void walk_delayed_load(std::string_view bytes, std::size_t file_size, const std::string& source) {
  if (bytes.empty()) return;  // OpenVDB reads nothing then
  ByteWalker value(bytes, source, "corrupt OpenVDB file: the stated size of delayed-load metadata ends");
  const auto leaves = value.number<std::uint32_t>("leaf count");
  if (leaves > file_size / kMinFileBytesPerLeaf)
    value.corrupt("delayed-load metadata claims " + std::to_string(leaves) +
                  " leaves where the file holds at most " + std::to_string(file_size / kMinFileBytesPerLeaf));
  walk_delayed_load_array(value, leaves, sizeof(std::int8_t), "delayed-load leaf masks", false);
  walk_delayed_load_array(value, leaves, sizeof(std::int64_t), "delayed-load leaf sizes", true);
}

}  // namespace

void walk_metadata(ByteWalker& in) {
  const auto count = in.number<std::uint32_t>("metadata count");
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::string_view name = in.sized("metadata name");
    const std::string_view type = in.sized("metadata type");
    const std::string_view value = in.sized("metadata value");
    if (type == kDelayedLoadType) {
      walk_delayed_load(value, in.size(), in.source());
      continue;
    }
    const std::size_t expected = fixed_size(type);
    if (expected != 0 && value.size() != expected)
      in.corrupt("metadata " + quoted(name) + " of type " + std::string(type) + " holds " +
                 std::to_string(value.size()) + " bytes, not " + std::to_string(expected));
  }
}

}  // namespace mr::plugins::vdb
