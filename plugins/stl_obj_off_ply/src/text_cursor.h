#pragma once
// Line and token scanning over a text file held in memory, for the ASCII
// readers. Numbers are parsed with std::from_chars (locale-independent, exact
// round trip, fast). Every failure names the file and the line.

#include <mr/core/errors.h>

#include <cstdint>
#include <string>
#include <string_view>

namespace mr::plugins::stl_obj_off_ply {

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

bool is_space(char c);
/// The token in single quotes, cut to 40 characters, for error messages.
std::string quoted(std::string_view token);
std::string_view trim(std::string_view text);
bool iequals(std::string_view a, std::string_view b);
bool istarts_with(std::string_view text, std::string_view prefix);

/// Parse a whole token; false if it is not (entirely) a number.
bool parse_number(std::string_view token, double& value);
bool parse_number(std::string_view token, float& value);
bool parse_integer(std::string_view token, std::int64_t& value);

class TextCursor {
 public:
  TextCursor(std::string path, std::string_view text) : path_(std::move(path)), text_(text) {}

  /// The next physical line without its end-of-line characters; false at the end.
  bool next_line(std::string_view& line);
  /// The next line that is neither blank nor a comment starting with `comment`.
  bool next_content_line(std::string_view& line, char comment);

  std::size_t line_number() const { return line_number_; }
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return text_.size() - pos_; }
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& problem) const;
  double number(Tokens& tokens, const char* what) const;
  std::int64_t integer(Tokens& tokens, const char* what) const;

 private:
  std::string path_;
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_number_ = 0;
};

}  // namespace mr::plugins::stl_obj_off_ply
