#include "vdb_declared_sizes.h"

#include <mr/core/errors.h>

#include <cstdint>
#include <cstring>
#include <optional>

namespace mr::plugins::vdb {
namespace {

constexpr std::int64_t kMagic = 0x56444220;  // " BDV"
constexpr std::uint32_t kFirstWalkedVersion = 222, kLastWalkedVersion = 224;
constexpr std::size_t kLibraryVersionBytes = 8, kUuidBytes = 36;  // two uint32; the UUID as text

// Bytes of a metadata value of OpenVDB's fixed-size types; 0 for the others
// (strings, and types it does not know, read by their stated size).
std::size_t fixed_size(std::string_view type) {
  struct Known {
    std::string_view type;
    std::size_t bytes;
  };
  static constexpr Known kKnown[] = {{"bool", 1},   {"int32", 4},  {"int64", 8},  {"float", 4},
                                     {"double", 8}, {"vec2i", 8},  {"vec2s", 8},  {"vec2d", 16},
                                     {"vec3i", 12}, {"vec3s", 12}, {"vec3d", 24}, {"vec4i", 16},
                                     {"vec4s", 16}, {"vec4d", 32}, {"mat4s", 64}, {"mat4d", 128}};
  for (const Known& known : kKnown)
    if (known.type == type) return known.bytes;
  return 0;
}

class Walker {
 public:
  Walker(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  std::size_t left() const { return bytes_.size() - at_; }
  std::size_t at() const { return at_; }
  void seek(std::size_t to) { at_ = to; }

  template <typename T>
  std::optional<T> number() {
    if (left() < sizeof(T)) return std::nullopt;
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));  // little-endian, as OpenVDB writes it
    at_ += sizeof(T);
    return value;
  }
  bool skip(std::size_t n) {
    if (left() < n) return false;
    at_ += n;
    return true;
  }
  // A length and that many bytes (names, metadata values): a length past the
  // end is what OpenVDB would allocate before finding the file too short.
  std::optional<std::string_view> sized(const char* what) {
    const auto length = number<std::uint32_t>();
    if (!length) return std::nullopt;
    if (*length > left())
      throw InputError(source_, "corrupt OpenVDB file: the " + std::string(what) + " claims " +
                                    std::to_string(*length) + " bytes where " + std::to_string(left()) +
                                    " remain");
    const std::string_view text = bytes_.substr(at_, *length);
    at_ += *length;
    return text;
  }
  // Metadata: a count, then per entry a name, a type name and a sized
  // value. OpenVDB reads a value of a fixed-size type by its type, not by
  // the size written before it, so a size that differs would leave it
  // reading the rest of the file out of step.
  bool metadata() {
    const auto count = number<std::int32_t>();
    if (!count || *count < 0) return false;
    for (std::int32_t i = 0; i < *count; ++i) {
      const auto name = sized("metadata name");
      const auto type = name ? sized("metadata type") : std::nullopt;
      const auto value = type ? sized("metadata value") : std::nullopt;
      if (!value) return false;
      const std::size_t expected = fixed_size(*type);
      if (expected != 0 && value->size() != expected)
        throw InputError(source_, "corrupt OpenVDB file: metadata \"" + std::string(*name) + "\" of type " +
                                      std::string(*type) + " holds " + std::to_string(value->size()) +
                                      " bytes, not " + std::to_string(expected));
    }
    return true;
  }

 private:
  std::string_view bytes_;
  const std::string& source_;
  std::size_t at_ = 0;
};

// One grid's descriptor, metadata and transform name; then on to the next
// grid through the descriptor's end offset, where the file has offsets.
bool walk_grid(Walker& in, bool has_offsets) {
  if (!in.sized("grid name") || !in.sized("grid type") || !in.sized("instance parent name")) return false;
  in.number<std::int64_t>();  // grid position
  in.number<std::int64_t>();  // block position
  const auto end = in.number<std::int64_t>();
  if (!end || !in.number<std::uint32_t>()) return false;  // then the compression flags
  if (!in.metadata() || !in.sized("transform type")) return false;
  if (!has_offsets || *end <= static_cast<std::int64_t>(in.at()) ||
      *end > static_cast<std::int64_t>(in.at() + in.left()))
    return false;
  in.seek(static_cast<std::size_t>(*end));
  return true;
}

}  // namespace

void check_vdb_declared_sizes(std::string_view bytes, const std::string& source) {
  Walker in(bytes, source);
  const auto magic = in.number<std::int64_t>();
  const auto version = in.number<std::uint32_t>();
  if (!magic || *magic != kMagic || !version || *version < kFirstWalkedVersion ||
      *version > kLastWalkedVersion)
    return;
  const auto has_offsets = in.skip(kLibraryVersionBytes) ? in.number<std::uint8_t>() : std::nullopt;
  if (!has_offsets || !in.skip(kUuidBytes) || !in.metadata()) return;
  const auto grids = in.number<std::int32_t>();
  if (!grids) return;
  for (std::int32_t g = 0; g < *grids; ++g)
    if (!walk_grid(in, *has_offsets != 0)) return;
}

}  // namespace mr::plugins::vdb
