#pragma once
// A cursor over a file held in memory, for the text formats and for the
// text-framed binary sections of MSH. Every read is bounds-checked and every
// failure throws mr::InputError naming the file and the line.

#include <mr/core/errors.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

namespace mr::plugins::tet {

class TextCursor {
 public:
  /// `comment` starts a comment that runs to the end of the line ('\0': none).
  TextCursor(std::string path, std::string_view data, char comment = '\0')
      : path_(std::move(path)), data_(data), comment_(comment) {}

  const std::string& path() const { return path_; }
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return data_.size() - pos_; }
  /// True when only whitespace (and comments) is left.
  bool at_end();

  /// The next whitespace-separated token; throws at the end of the file.
  std::string_view token(const char* what);
  /// The next token if there is one, or an empty view at the end of the file.
  std::string_view token_or_empty();
  /// Reads the next token and throws unless it equals `expected`.
  void expect(std::string_view expected);
  /// Moves to the start of the next line.
  void skip_line();
  /// Moves past the next occurrence of `marker`; false (and no move) if absent.
  bool skip_past(std::string_view marker);

  std::uint64_t unsigned_integer(const char* what);
  std::int64_t signed_integer(const char* what);
  std::int32_t int32(const char* what);
  double real(const char* what);

  /// Throws unless `count` entries of at least `min_bytes` each can still fit
  /// in the file: the guard to call before allocating for a count from the file.
  void require(std::uint64_t count, std::uint64_t min_bytes, const char* what) const;

  /// Throws unless `count` more bytes are in the file.
  void require_bytes(std::size_t count, const char* what) const;

  /// Raw binary value at the cursor, in file byte order.
  template <class T>
  T raw(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    require_bytes(sizeof(T), what);
    T value;
    std::memcpy(&value, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  /// Pointer to `count` raw bytes at the cursor, which is moved past them.
  const char* take(std::size_t count, const char* what);

  [[noreturn]] void fail(const std::string& problem) const;

 private:
  void skip_space();
  std::size_t line_number() const;

  std::string path_;
  std::string_view data_;
  char comment_;
  std::size_t pos_ = 0;
};

}  // namespace mr::plugins::tet
