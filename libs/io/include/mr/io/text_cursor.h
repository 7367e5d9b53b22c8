#pragma once
// A cursor over a file held in memory, for the text formats (line by line or
// token by token) and for text-framed binary data such as MSH sections.
// Numbers are parsed with std::from_chars (locale-independent, exact round
// trip). Every read is bounds-checked and every failure throws
// mr::InputError naming the file and the line.

#include <mr/core/errors.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

namespace mr::io {

bool is_space(char c);
/// The token in single quotes for error messages: cut to 40 characters,
/// unprintable bytes shown as '?'.
std::string quoted(std::string_view token);
std::string_view trim(std::string_view text);
bool iequals(std::string_view a, std::string_view b);
bool istarts_with(std::string_view text, std::string_view prefix);

/// Parse a whole token (a leading '+' allowed); false if it is not entirely
/// a number in range.
bool parse_number(std::string_view token, double& value);
bool parse_number(std::string_view token, float& value);
bool parse_integer(std::string_view token, std::int64_t& value);

/// Splits a line into whitespace-separated tokens.
class Tokens {
 public:
  explicit Tokens(std::string_view line) : rest_(line) {}
  /// The next token, or an empty view at the end of the line.
  std::string_view next();
  bool empty();
  std::string_view rest() const { return rest_; }

 private:
  std::string_view rest_;
};

class TextCursor {
 public:
  /// `comment` starts a comment that runs to the end of the line, skipped by
  /// the token reads ('\0': none).
  TextCursor(std::string path, std::string_view text, char comment = '\0')
      : path_(std::move(path)), text_(text), comment_(comment) {}

  const std::string& path() const { return path_; }
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return text_.size() - pos_; }
  /// The line of the last line, token or bytes read (1-based).
  std::size_t line_number() const;
  [[noreturn]] void fail(const std::string& problem) const;

  // Line by line.
  /// The next physical line without its end-of-line characters; false at the end.
  bool next_line(std::string_view& line);
  /// The next line that is neither blank nor starts with `comment`, trimmed.
  bool next_content_line(std::string_view& line, char comment);
  /// The next token of `tokens` (a line of this cursor) as a number; throws
  /// if it is missing or not a number in range.
  double number(Tokens& tokens, const char* what) const;
  std::int64_t integer(Tokens& tokens, const char* what) const;

  // Token by token, across lines.
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
  /// A number; out of range gives what strtod gives (infinity or zero).
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
    T value;
    std::memcpy(&value, take(sizeof(T), what), sizeof(T));
    return value;
  }
  /// Pointer to `count` raw bytes at the cursor, which is moved past them.
  const char* take(std::size_t count, const char* what);

 private:
  void skip_space();

  std::string path_;
  std::string_view text_;
  char comment_;
  std::size_t pos_ = 0;
  std::size_t item_start_ = 0;  ///< where the last read began, for line_number()
};

}  // namespace mr::io
