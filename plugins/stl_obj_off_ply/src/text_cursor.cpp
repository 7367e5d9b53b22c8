#include "text_cursor.h"

#include <algorithm>
#include <charconv>
#include <cstring>

namespace mr::plugins::stl_obj_off_ply {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

std::string quoted(std::string_view token) {
  std::string text(1, '\'');
  text.append(token.substr(0, 40)).push_back('\'');
  return text;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

namespace {
char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }
}  // namespace

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return lower(x) == lower(y);
         });
}

bool istarts_with(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() && iequals(text.substr(0, prefix.size()), prefix);
}

std::string_view Tokens::next() {
  std::size_t i = 0;
  while (i < rest_.size() && is_space(rest_[i])) ++i;
  std::size_t j = i;
  while (j < rest_.size() && !is_space(rest_[j])) ++j;
  const std::string_view token = rest_.substr(i, j - i);
  rest_.remove_prefix(j);
  return token;
}

bool Tokens::empty() {
  while (!rest_.empty() && is_space(rest_.front())) rest_.remove_prefix(1);
  return rest_.empty();
}

template <class T>
static bool parse_whole(std::string_view token, T& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return error == std::errc() && end == token.data() + token.size();
}

bool parse_number(std::string_view token, double& value) { return parse_whole(token, value); }
bool parse_number(std::string_view token, float& value) { return parse_whole(token, value); }
bool parse_integer(std::string_view token, std::int64_t& value) { return parse_whole(token, value); }

bool TextCursor::next_line(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const void* found = std::memchr(text_.data() + pos_, '\n', text_.size() - pos_);
  const std::size_t end = found ? static_cast<std::size_t>(static_cast<const char*>(found) - text_.data())
                                : text_.size();
  line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = found ? end + 1 : end;
  ++line_number_;
  return true;
}

bool TextCursor::next_content_line(std::string_view& line, char comment) {
  while (next_line(line)) {
    const std::string_view content = trim(line);
    if (!content.empty() && content.front() != comment) {
      line = content;
      return true;
    }
  }
  return false;
}

void TextCursor::fail(const std::string& problem) const {
  throw InputError(path_, "line " + std::to_string(line_number_) + ": " + problem);
}

double TextCursor::number(Tokens& tokens, const char* what) const {
  const std::string_view token = tokens.next();
  double value = 0;
  if (token.empty()) fail(std::string("missing ") + what);
  if (!parse_number(token, value)) fail(quoted(token) + " is not a number (" + what + ")");
  return value;
}

std::int64_t TextCursor::integer(Tokens& tokens, const char* what) const {
  const std::string_view token = tokens.next();
  std::int64_t value = 0;
  if (token.empty()) fail(std::string("missing ") + what);
  if (!parse_integer(token, value)) fail(quoted(token) + " is not an integer (" + what + ")");
  return value;
}

}  // namespace mr::plugins::stl_obj_off_ply
