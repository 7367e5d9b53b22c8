#pragma once
// A buffered output file for the format writers: text and binary values go
// into a memory buffer written out in large blocks. Every stream failure
// (open, write, close) throws mr::RunError naming the file. Writers are handed
// a temporary path by the I/O core (see atomic_file.h), so a failed write
// never leaves a half-written destination.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>

namespace mr::io {

class OutputFile {
 public:
  explicit OutputFile(const std::filesystem::path& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  OutputFile& operator<<(std::string_view text) {
    write_raw(text.data(), text.size());
    return *this;
  }
  OutputFile& operator<<(char c) {
    write_raw(&c, 1);
    return *this;
  }
  /// Shortest text that reads back as exactly `value`.
  OutputFile& operator<<(double value);
  OutputFile& operator<<(float value);
  OutputFile& operator<<(std::int64_t value);
  OutputFile& operator<<(int value) { return *this << static_cast<std::int64_t>(value); }
  OutputFile& operator<<(std::uint32_t value) { return *this << static_cast<std::int64_t>(value); }

  /// Appends the bytes of `value` in the host's byte order.
  template <class T>
  void write_native(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    write_raw(&value, sizeof(T));
  }

  /// Appends the bytes of `value` in little-endian order.
  template <class T>
  void write_le(T value) {
    static_assert(std::is_arithmetic_v<T>);
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
    write_raw(bytes, sizeof(T));
  }

  /// Appends raw bytes as they are in memory.
  void write_raw(const void* data, std::size_t size) {
    // Inline fast path: writers append millions of small values.
    if (size <= kBufferSize - used_) {
      std::memcpy(buffer_.data() + used_, data, size);
      used_ += size;
    } else {
      write_past_buffer(data, size);
    }
  }

  /// Flushes and closes; throws RunError on failure. Must be called once at
  /// the end: the destructor only releases the handle.
  void close();

 private:
  static constexpr std::size_t kBufferSize = std::size_t(1) << 20;

  template <class T>
  OutputFile& write_number(T value);
  void write_past_buffer(const void* data, std::size_t size);
  void flush();
  [[noreturn]] void fail(const std::string& action) const;

  std::string path_;
  std::FILE* file_ = nullptr;
  std::string buffer_;  ///< kBufferSize bytes, of which the first used_ are pending
  std::size_t used_ = 0;
};

/// Writes `bytes` as the whole content of `path`; throws RunError on failure.
void write_file_bytes(const std::filesystem::path& path, std::string_view bytes);

}  // namespace mr::io
