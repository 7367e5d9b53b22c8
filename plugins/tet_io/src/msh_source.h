#pragma once
// The two encodings of MSH section bodies behind one interface, so that each
// section is parsed by one template for ASCII and binary alike.

#include <mr/io/text_cursor.h>

#include <bit>
#include <cstdint>

namespace mr::plugins::tet {

/// How the $MeshFormat header says the body is encoded.
struct MshEncoding {
  bool binary = false;
  bool swap_bytes = false;  ///< binary written on a machine of the other endianness
  int size_t_bytes = 8;     ///< width of size_t values in MSH 4 binary files
};

class AsciiSource {
 public:
  explicit AsciiSource(io::TextCursor& cursor) : cursor_(cursor) {}
  std::uint64_t size(const char* what) { return cursor_.unsigned_integer(what); }
  std::int32_t int32(const char* what) { return cursor_.int32(what); }
  double real(const char* what) { return cursor_.real(what); }
  /// Throws unless `count` entries of `values` numbers each can fit in what
  /// is left (an ASCII number takes at least 2 bytes with its separator).
  void require(std::uint64_t count, std::uint64_t values, const char* what) const {
    cursor_.require(count, 2 * values, what);
  }
  io::TextCursor& cursor() { return cursor_; }

 private:
  io::TextCursor& cursor_;
};

class BinarySource {
 public:
  BinarySource(io::TextCursor& cursor, const MshEncoding& encoding) : cursor_(cursor), encoding_(encoding) {}
  std::uint64_t size(const char* what) {
    if (encoding_.size_t_bytes == 4) return value<std::uint32_t>(what);
    return value<std::uint64_t>(what);
  }
  std::int32_t int32(const char* what) { return value<std::int32_t>(what); }
  double real(const char* what) { return std::bit_cast<double>(value<std::uint64_t>(what)); }
  /// Throws unless `count` entries of `values` numbers each can fit in what
  /// is left (no binary value is smaller than 4 bytes).
  void require(std::uint64_t count, std::uint64_t values, const char* what) const {
    cursor_.require(count, 4 * values, what);
  }
  io::TextCursor& cursor() { return cursor_; }

 private:
  template <class T>
  T value(const char* what) {
    T v = cursor_.raw<T>(what);
    if (encoding_.swap_bytes) v = byteswap(v);
    return v;
  }
  template <class T>
  static T byteswap(T v) {
    using U = std::make_unsigned_t<T>;
    U u = static_cast<U>(v), r = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i, u >>= 8) r = static_cast<U>((r << 8) | (u & 0xff));
    return static_cast<T>(r);
  }

  io::TextCursor& cursor_;
  MshEncoding encoding_;
};

}  // namespace mr::plugins::tet
