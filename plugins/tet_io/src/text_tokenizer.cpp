#include "text_tokenizer.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace mr::plugins::tet {
namespace {

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == '\f' || c == '\v'; }

// std::from_chars rejects a leading '+', which some writers emit.
std::string_view strip_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  return token;
}

std::string quoted(std::string_view token) {
  constexpr std::size_t shown = 40;
  std::string text(token.substr(0, shown));
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return "'" + text + (token.size() > shown ? "...'" : "'");
}

template <class T>
T parse_integer(TextCursor& cursor, const char* what) {
  const std::string_view token = strip_plus(cursor.token(what));
  T value{};
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec == std::errc::result_out_of_range) cursor.fail(std::string(what) + " " + quoted(token) + " is out of range");
  if (ec != std::errc() || end != token.data() + token.size())
    cursor.fail(std::string("expected an integer for ") + what + ", found " + quoted(token));
  return value;
}

}  // namespace

void TextCursor::skip_space() {
  while (pos_ < data_.size()) {
    const char c = data_[pos_];
    if (is_space(c)) {
      ++pos_;
    } else if (comment_ != '\0' && c == comment_) {
      skip_line();
    } else {
      return;
    }
  }
}

bool TextCursor::at_end() {
  skip_space();
  return pos_ == data_.size();
}

std::string_view TextCursor::token_or_empty() {
  skip_space();
  const std::size_t start = pos_;
  while (pos_ < data_.size() && !is_space(data_[pos_])) ++pos_;
  return data_.substr(start, pos_ - start);
}

std::string_view TextCursor::token(const char* what) {
  const std::string_view t = token_or_empty();
  if (t.empty()) fail(std::string("truncated: unexpected end of file while reading ") + what);
  return t;
}

void TextCursor::expect(std::string_view expected) {
  const std::string_view t = token_or_empty();
  if (t != expected)
    fail("expected " + std::string(expected) + ", found " + (t.empty() ? "the end of the file" : quoted(t)));
}

void TextCursor::skip_line() {
  const std::size_t newline = data_.find('\n', pos_);
  pos_ = newline == std::string_view::npos ? data_.size() : newline + 1;
}

bool TextCursor::skip_past(std::string_view marker) {
  const std::size_t found = data_.find(marker, pos_);
  if (found == std::string_view::npos) return false;
  pos_ = found + marker.size();
  return true;
}

std::uint64_t TextCursor::unsigned_integer(const char* what) { return parse_integer<std::uint64_t>(*this, what); }
std::int64_t TextCursor::signed_integer(const char* what) { return parse_integer<std::int64_t>(*this, what); }
std::int32_t TextCursor::int32(const char* what) { return parse_integer<std::int32_t>(*this, what); }

double TextCursor::real(const char* what) {
  const std::string_view token = strip_plus(this->token(what));
  double value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  // Out of range means overflow to infinity or underflow to zero: keep what
  // strtod would give, the consistency check rejects infinities later.
  if (ec == std::errc::result_out_of_range) return std::strtod(std::string(token).c_str(), nullptr);
  if (ec != std::errc() || end != token.data() + token.size())
    fail(std::string("expected a number for ") + what + ", found " + quoted(token));
  return value;
}

void TextCursor::require(std::uint64_t count, std::uint64_t min_bytes, const char* what) const {
  const std::uint64_t left = remaining();
  if (min_bytes != 0 && count > left / min_bytes)
    fail(std::string("truncated or corrupt: ") + what + " declares " + std::to_string(count) +
         " entries but only " + std::to_string(left) + " bytes remain");
}

void TextCursor::require_bytes(std::size_t count, const char* what) const {
  if (count > remaining()) fail(std::string("truncated: unexpected end of file while reading ") + what);
}

const char* TextCursor::take(std::size_t count, const char* what) {
  require_bytes(count, what);
  const char* start = data_.data() + pos_;
  pos_ += count;
  return start;
}

std::size_t TextCursor::line_number() const {
  return 1 + static_cast<std::size_t>(std::count(data_.begin(), data_.begin() + static_cast<std::ptrdiff_t>(pos_), '\n'));
}

void TextCursor::fail(const std::string& problem) const {
  throw InputError(path_, "line " + std::to_string(line_number()) + ": " + problem);
}

}  // namespace mr::plugins::tet
