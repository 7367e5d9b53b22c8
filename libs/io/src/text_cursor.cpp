#include <mr/io/text_cursor.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>

namespace mr::io {
namespace {

char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

// std::from_chars over the whole token; it rejects a leading '+', which some
// writers emit, so one is skipped first.
template <class T>
std::errc parse_whole(std::string_view token, T& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::errc::invalid_argument;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc()) return error;
  return end == token.data() + token.size() ? std::errc() : std::errc::invalid_argument;
}

std::string out_of_range(std::string_view token, const char* what) {
  return std::string(what) + " " + quoted(token) + " is out of range";
}

template <class T>
T integer_or_fail(const TextCursor& cursor, std::string_view token, const char* what) {
  T value{};
  const std::errc error = parse_whole(token, value);
  if (error == std::errc::result_out_of_range) cursor.fail(out_of_range(token, what));
  if (error != std::errc())
    cursor.fail(std::string("expected an integer for ") + what + ", found " + quoted(token));
  return value;
}

// Out of range means overflow to infinity or underflow to zero; with
// `lenient` the value strtod gives is kept (the consistency check of the I/O
// core rejects infinities later), otherwise it is an error.
double real_or_fail(const TextCursor& cursor, std::string_view token, const char* what, bool lenient) {
  double value = 0;
  const std::errc error = parse_whole(token, value);
  if (error == std::errc::result_out_of_range) {
    if (!lenient) cursor.fail(out_of_range(token, what));
    return std::strtod(std::string(token).c_str(), nullptr);
  }
  if (error != std::errc())
    cursor.fail(std::string("expected a number for ") + what + ", found " + quoted(token));
  return value;
}

}  // namespace

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

std::string quoted(std::string_view token) {
  constexpr std::size_t shown = 40;
  std::string text(token.substr(0, shown));
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return "'" + text + (token.size() > shown ? "...'" : "'");
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return lower(x) == lower(y); });
}

bool istarts_with(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() && iequals(text.substr(0, prefix.size()), prefix);
}

bool parse_number(std::string_view token, double& value) { return parse_whole(token, value) == std::errc(); }
bool parse_number(std::string_view token, float& value) { return parse_whole(token, value) == std::errc(); }
bool parse_integer(std::string_view token, std::int64_t& value) {
  return parse_whole(token, value) == std::errc();
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

std::size_t TextCursor::line_number() const {
  const auto begin = text_.begin();
  return 1 +
         static_cast<std::size_t>(std::count(begin, begin + static_cast<std::ptrdiff_t>(item_start_), '\n'));
}

void TextCursor::fail(const std::string& problem) const {
  throw InputError(path_, "line " + std::to_string(line_number()) + ": " + problem);
}

bool TextCursor::next_line(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const void* found = std::memchr(text_.data() + pos_, '\n', text_.size() - pos_);
  const std::size_t end =
      found ? static_cast<std::size_t>(static_cast<const char*>(found) - text_.data()) : text_.size();
  line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  item_start_ = pos_;
  pos_ = found ? end + 1 : end;
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

double TextCursor::number(Tokens& tokens, const char* what) const {
  const std::string_view t = tokens.next();
  if (t.empty()) fail(std::string("missing ") + what);
  return real_or_fail(*this, t, what, false);
}

std::int64_t TextCursor::integer(Tokens& tokens, const char* what) const {
  const std::string_view t = tokens.next();
  if (t.empty()) fail(std::string("missing ") + what);
  return integer_or_fail<std::int64_t>(*this, t, what);
}

void TextCursor::skip_space() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
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
  return pos_ == text_.size();
}

std::string_view TextCursor::token_or_empty() {
  skip_space();
  item_start_ = pos_;
  while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
  return text_.substr(item_start_, pos_ - item_start_);
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
  const std::size_t newline = text_.find('\n', pos_);
  pos_ = newline == std::string_view::npos ? text_.size() : newline + 1;
  item_start_ = pos_;
}

bool TextCursor::skip_past(std::string_view marker) {
  const std::size_t found = text_.find(marker, pos_);
  if (found == std::string_view::npos) return false;
  pos_ = found + marker.size();
  item_start_ = pos_;
  return true;
}

std::uint64_t TextCursor::unsigned_integer(const char* what) {
  return integer_or_fail<std::uint64_t>(*this, token(what), what);
}
std::int64_t TextCursor::signed_integer(const char* what) {
  return integer_or_fail<std::int64_t>(*this, token(what), what);
}
std::int32_t TextCursor::int32(const char* what) {
  return integer_or_fail<std::int32_t>(*this, token(what), what);
}
double TextCursor::real(const char* what) { return real_or_fail(*this, token(what), what, true); }

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
  item_start_ = pos_;
  require_bytes(count, what);
  const char* start = text_.data() + pos_;
  pos_ += count;
  return start;
}

}  // namespace mr::io
