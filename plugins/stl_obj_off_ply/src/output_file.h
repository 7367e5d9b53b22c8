#pragma once
// A buffered output file for the writers: text and binary appends go to a
// memory buffer flushed in large blocks; every stream failure (open, write,
// close) throws mr::RunError naming the file.

#include <mr/core/errors.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>

namespace mr::plugins::stl_obj_off_ply {

class OutputFile {
 public:
  explicit OutputFile(const std::filesystem::path& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  OutputFile& operator<<(std::string_view text);
  OutputFile& operator<<(char c);
  /// Shortest text that reads back as exactly `value`.
  OutputFile& operator<<(double value);
  OutputFile& operator<<(float value);
  OutputFile& operator<<(std::int64_t value);
  OutputFile& operator<<(int value) { return *this << static_cast<std::int64_t>(value); }
  OutputFile& operator<<(std::uint32_t value) { return *this << static_cast<std::int64_t>(value); }

  /// Appends the bytes of `value` in little-endian order (the host order, checked).
  template <class T>
  void write_le(T value) {
    static_assert(std::is_arithmetic_v<T>);
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    append(bytes, sizeof(T));
  }

  /// Appends raw bytes (arrays of little-endian values).
  void write_raw(const void* data, std::size_t size) { append(static_cast<const char*>(data), size); }

  /// Flushes and closes; throws RunError on failure. Must be called once at the end.
  void close();

 private:
  void append(const char* data, std::size_t size);
  void flush();

  std::string path_;
  std::FILE* file_ = nullptr;
  std::string buffer_;
};

}  // namespace mr::plugins::stl_obj_off_ply
