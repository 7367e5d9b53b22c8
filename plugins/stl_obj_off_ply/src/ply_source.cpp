#include "ply_source.h"

#include <mr/io/text_cursor.h>

#include <bit>
#include <cmath>

namespace mr::plugins::stl_obj_off_ply {
namespace {

std::string count_problem(const PlyElement& element, std::size_t remaining) {
  return "element '" + element.name + "' claims " + std::to_string(element.count) + " entries but only " +
         std::to_string(remaining) + " bytes of data remain";
}

template <class T>
T byte_swapped(T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

}  // namespace

void PlyBinarySource::check_count(const PlyElement& element) const {
  const std::uint64_t size = element.min_binary_size();
  if (size > 0 && element.count > reader_.remaining() / size)
    fail(count_problem(element, reader_.remaining()));
}

template <class T>
T PlyBinarySource::raw(const char* what) {
  const T value = reader_.read<T>(what);
  return swap_ ? byte_swapped(value) : value;
}

template <class Result>
Result PlyBinarySource::read_as(PlyType type) {
  constexpr const char* what = "a PLY property value (the body is truncated)";
  switch (type) {
    case PlyType::int8:
      return static_cast<Result>(raw<std::int8_t>(what));
    case PlyType::uint8:
      return static_cast<Result>(raw<std::uint8_t>(what));
    case PlyType::int16:
      return static_cast<Result>(raw<std::int16_t>(what));
    case PlyType::uint16:
      return static_cast<Result>(raw<std::uint16_t>(what));
    case PlyType::int32:
      return static_cast<Result>(raw<std::int32_t>(what));
    case PlyType::uint32:
      return static_cast<Result>(raw<std::uint32_t>(what));
    case PlyType::float32:
      return static_cast<Result>(raw<float>(what));
    case PlyType::float64:
      return static_cast<Result>(raw<double>(what));
  }
  return Result{};
}

double PlyBinarySource::number(PlyType type) { return read_as<double>(type); }

std::int64_t PlyBinarySource::integer(PlyType type) {
  if (type != PlyType::float32 && type != PlyType::float64) return read_as<std::int64_t>(type);
  const double value = number(type);
  if (!(std::abs(value) < 9e15) || value != std::floor(value))
    fail("expected an integer, found " + std::to_string(value));
  return static_cast<std::int64_t>(value);
}

std::int64_t PlyBinarySource::list_count(const PlyProperty& property) {
  const std::int64_t count = integer(property.count_type);
  if (count < 0) fail("negative length " + std::to_string(count) + " for list '" + property.name + "'");
  reader_.require(static_cast<std::uint64_t>(count), ply_type_size(property.type), "the items of a PLY list");
  return count;
}

void PlyBinarySource::skip(PlyType type, std::int64_t count) {
  reader_.require(static_cast<std::uint64_t>(count), ply_type_size(type), "skipped PLY values");
  reader_.skip(static_cast<std::size_t>(count) * ply_type_size(type), "skipped PLY values");
}

// ASCII: every value is a token of at least one character plus a separator.

void PlyAsciiSource::check_count(const PlyElement& element) const {
  const std::uint64_t values = element.properties.size();
  if (values > 0 && element.count > (size_ - pos_ + 1) / (2 * values))
    fail(count_problem(element, size_ - pos_));
}

void PlyAsciiSource::fail(const std::string& problem) const {
  throw InputError(path_, problem + " (at byte " + std::to_string(pos_) + " of the body)");
}

std::string_view PlyAsciiSource::token() {
  while (pos_ < size_ && io::is_space(data_[pos_])) ++pos_;
  const std::size_t start = pos_;
  while (pos_ < size_ && !io::is_space(data_[pos_])) ++pos_;
  if (start == pos_) fail("the body is truncated: a value is missing");
  return {data_ + start, pos_ - start};
}

double PlyAsciiSource::number(PlyType) {
  const std::string_view text = token();
  double value = 0;
  if (!io::parse_number(text, value)) fail(io::quoted(text) + " is not a number");
  return value;
}

std::int64_t PlyAsciiSource::integer(PlyType type) {
  const std::string_view text = token();
  std::int64_t value = 0;
  if (io::parse_integer(text, value)) return value;
  double real = 0;
  if (!ply_type_is_integer(type) && io::parse_number(text, real) && std::abs(real) < 9e15 &&
      real == std::floor(real))
    return static_cast<std::int64_t>(real);
  fail(io::quoted(text) + " is not an integer");
}

std::int64_t PlyAsciiSource::list_count(const PlyProperty& property) {
  const std::int64_t count = integer(property.count_type);
  if (count < 0) fail("negative length " + std::to_string(count) + " for list '" + property.name + "'");
  if (static_cast<std::uint64_t>(count) > (size_ - pos_) / 2)
    fail("list '" + property.name + "' claims " + std::to_string(count) + " items but only " +
         std::to_string(size_ - pos_) + " bytes remain");
  return count;
}

void PlyAsciiSource::skip(PlyType, std::int64_t count) {
  for (std::int64_t i = 0; i < count; ++i) token();
}

}  // namespace mr::plugins::stl_obj_off_ply
