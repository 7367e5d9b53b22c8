#include "draco_declared_sizes.h"

#include <mr/core/errors.h>

#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

namespace mr::plugins::detail {
namespace {

// The layout follows Draco's bitstream (versions 1.0 to 2.2): an 11-byte
// header, optional metadata, then the connectivity's counts, fixed 32-bit
// before version 2.0 and LEB128 varints after.
constexpr std::uint16_t kMetadataFlag = 0x8000;
constexpr std::uint8_t kTriangularMesh = 1;
constexpr std::uint8_t kSequential = 0;
constexpr std::uint8_t kEdgebreaker = 1;

constexpr int version(int major, int minor) { return (major << 8) | minor; }

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}

  std::optional<std::uint8_t> byte() {
    if (at_ >= bytes_.size()) return std::nullopt;
    return static_cast<std::uint8_t>(bytes_[at_++]);
  }
  std::optional<std::uint32_t> fixed32() {
    if (bytes_.size() - at_ < 4) return std::nullopt;
    std::uint32_t value = 0;
    for (int k = 0; k < 4; ++k) value |= std::uint32_t(static_cast<std::uint8_t>(bytes_[at_++])) << (8 * k);
    return value;  // little-endian, as Draco writes it
  }
  // LEB128 of at most 5 bytes, its bits past 32 dropped: what Draco's
  // decoder makes of it (a longer one it refuses).
  std::optional<std::uint32_t> varint() {
    std::uint64_t value = 0;
    for (int shift = 0; shift < 35; shift += 7) {
      const auto b = byte();
      if (!b) return std::nullopt;
      value |= std::uint64_t(*b & 0x7f) << shift;
      if (!(*b & 0x80)) return static_cast<std::uint32_t>(value);
    }
    return std::nullopt;
  }
  std::optional<std::uint32_t> count(int bitstream) {
    return bitstream < version(2, 0) ? fixed32() : varint();
  }
  bool skip(std::uint64_t n) {
    if (bytes_.size() - at_ < n) return false;
    at_ += n;
    return true;
  }
  bool at_prefix(std::string_view text) const { return bytes_.substr(at_, text.size()) == text; }

 private:
  std::string_view bytes_;
  std::size_t at_ = 0;
};

// One metadata block: entries (name, sized value), then named sub-blocks,
// each written in full before the next name. Iterative, so that nesting
// cannot exhaust the stack; false when the bytes end first.
bool skip_metadata(Reader& in) {
  std::vector<std::uint32_t> subs_left{1};  // per open level: blocks still to read
  while (!subs_left.empty()) {
    if (subs_left.back() == 0) {
      subs_left.pop_back();
      continue;
    }
    --subs_left.back();
    if (subs_left.size() > 1) {  // a sub-block is preceded by its name
      const auto name = in.byte();
      if (!name || !in.skip(*name)) return false;
    }
    const auto entries = in.varint();
    if (!entries) return false;
    for (std::uint32_t e = 0; e < *entries; ++e) {
      const auto name = in.byte();
      if (!name || !in.skip(*name)) return false;
      const auto size = in.varint();
      if (!size || !in.skip(*size)) return false;
    }
    const auto subs = in.varint();
    if (!subs) return false;
    subs_left.push_back(*subs);
  }
  return true;
}

bool skip_geometry_metadata(Reader& in) {
  const auto attributes = in.varint();
  if (!attributes) return false;
  for (std::uint32_t a = 0; a < *attributes; ++a)
    if (!in.varint() || !skip_metadata(in)) return false;
  return skip_metadata(in);
}

// The counts the decoder allocates for, in bitstream order, as far as the
// bytes go (Draco allocates for each as it reads it); empty for an unknown method.
std::vector<std::uint32_t> declared_counts(Reader& in, int bitstream, std::uint8_t method) {
  std::vector<std::uint32_t> counts;
  const auto take = [&](std::optional<std::uint32_t> value) {
    if (value) counts.push_back(*value);
    return value.has_value();
  };
  if (method == kSequential) {
    const auto faces_or_points = [&] { return bitstream < version(2, 2) ? in.fixed32() : in.varint(); };
    if (take(faces_or_points())) take(faces_or_points());
    return counts;
  }
  if (method != kEdgebreaker || !in.byte()) return counts;                      // the traversal decoder type
  if (bitstream < version(2, 2) && !take(in.count(bitstream))) return counts;   // new vertices
  if (!take(in.count(bitstream)) || !take(in.count(bitstream))) return counts;  // encoded vertices, faces
  if (!in.byte()) return counts;                                                // attribute data
  if (take(in.count(bitstream))) take(in.count(bitstream));                     // symbols, split symbols
  return counts;
}

}  // namespace

void check_draco_declared_sizes(std::string_view bytes, const std::string& source) {
  Reader in(bytes);
  if (!in.at_prefix("DRACO") || !in.skip(5)) return;
  const auto major = in.byte(), minor = in.byte(), type = in.byte(), method = in.byte();
  const auto flags_low = in.byte(), flags_high = in.byte();
  if (!flags_high || *type != kTriangularMesh) return;
  const int bitstream = version(*major, *minor);
  const std::uint16_t flags = static_cast<std::uint16_t>(*flags_low | (*flags_high << 8));
  if (bitstream >= version(1, 3) && (flags & kMetadataFlag) && !skip_geometry_metadata(in)) return;
  const double limit = kMaxDracoElementsPerByte * static_cast<double>(bytes.size());
  for (std::uint32_t count : declared_counts(in, bitstream, *method))
    if (count > limit)
      throw InputError(source, "not a valid Draco mesh: it claims " + std::to_string(count) +
                                   " elements in " + std::to_string(bytes.size()) +
                                   " bytes, more than any Draco mesh holds (" +
                                   std::to_string(static_cast<int>(kMaxDracoElementsPerByte)) + " per byte)");
}

}  // namespace mr::plugins::detail
