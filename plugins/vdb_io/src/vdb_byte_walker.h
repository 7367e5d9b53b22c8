#pragma once
// A cursor over the bytes of a VDB file for the walks that check, before
// OpenVDB reads the file, what OpenVDB will read (vdb_declared_sizes.cpp,
// vdb_metadata_walk.cpp, vdb_tree_walk.cpp). Every read is bounds-checked:
// what does not fit ends the walk with an InputError naming the file.

#include <mr/core/errors.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace mr::plugins::vdb {

class ByteWalker {
 public:
  /// `ends` says what it means when a read runs past the end of `bytes`:
  /// for a whole file, that it is truncated.
  ByteWalker(std::string_view bytes, const std::string& source,
             std::string_view ends = "truncated OpenVDB file: it ends")
      : bytes_(bytes), source_(source), ends_(ends) {}

  std::size_t size() const { return bytes_.size(); }
  std::size_t at() const { return at_; }
  std::size_t left() const { return bytes_.size() - at_; }

  /// The next n bytes, `what` naming them should the file end first.
  std::string_view take(std::size_t n, std::string_view what) {
    if (n > left()) truncated(what);
    const std::string_view taken = bytes_.substr(at_, n);
    at_ += n;
    return taken;
  }

  /// The next sizeof(T) bytes as a T, little-endian as OpenVDB writes it.
  template <typename T>
  T number(std::string_view what) {
    T value;
    std::memcpy(&value, take(sizeof(T), what).data(), sizeof(T));
    return value;
  }

  /// A uint32 length and that many bytes (names, metadata values). OpenVDB
  /// allocates and fills the stated length before it reads, so a length
  /// past the end is refused here.
  std::string_view sized(std::string_view what) {
    const auto length = number<std::uint32_t>(what);
    if (length > left())
      corrupt("the " + std::string(what) + " claims " + std::to_string(length) + " bytes where " +
              std::to_string(left()) + " remain");
    return take(length, what);
  }

  [[noreturn]] void corrupt(const std::string& problem) const {
    throw InputError(source_, "corrupt OpenVDB file: " + problem);
  }
  [[noreturn]] void truncated(std::string_view what) const {
    throw InputError(source_, std::string(ends_) + " inside the " + std::string(what));
  }
  [[noreturn]] void unsupported(const std::string& problem) const { throw InputError(source_, problem); }
  const std::string& source() const { return source_; }

 private:
  std::string_view bytes_;
  const std::string& source_;
  std::string_view ends_;
  std::size_t at_ = 0;
};

/// `text` (a name from the file) quoted for a message: at most 64 bytes,
/// bytes that do not print as '?'.
inline std::string quoted(std::string_view text) {
  constexpr std::size_t kMax = 64;
  std::string out = "\"";
  for (const char c : text.substr(0, kMax)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return out + (text.size() > kMax ? "...\"" : "\"");
}

/// The two sizes a Blosc 1 chunk's 16-byte header states.
struct BloscSizes {
  std::uint32_t uncompressed;  ///< bytes 4..7: what it decompresses to
  std::uint32_t compressed;    ///< bytes 12..15: its own length
};

/// The header of the Blosc chunk `chunk`. Blosc (1.21) reads the header
/// without knowing the chunk's length, then trusts the length it states as
/// the end of what it may read: a chunk shorter than its header, or shorter
/// than it claims, would be read past its end.
inline BloscSizes blosc_header(const ByteWalker& in, std::string_view chunk, std::string_view what) {
  constexpr std::size_t kHeaderBytes = 16;
  if (chunk.size() < kHeaderBytes)
    in.corrupt(std::string(what) + " are a Blosc chunk of " + std::to_string(chunk.size()) +
               " bytes, shorter than a Blosc header");
  BloscSizes sizes;
  std::memcpy(&sizes.uncompressed, chunk.data() + 4, 4);
  std::memcpy(&sizes.compressed, chunk.data() + 12, 4);
  if (sizes.compressed > chunk.size())
    in.corrupt(std::string(what) + " are a Blosc chunk of " + std::to_string(chunk.size()) +
               " bytes claiming " + std::to_string(sizes.compressed));
  return sizes;
}

}  // namespace mr::plugins::vdb
