#pragma once
// A buffered output file for the writers: text and raw binary values go into
// a large buffer flushed with fwrite. Any failure throws mr::RunError.

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>

namespace mr::plugins::tet {

class OutputFile {
 public:
  explicit OutputFile(const std::filesystem::path& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  OutputFile& text(std::string_view s);
  OutputFile& integer(std::int64_t value);
  /// Shortest decimal form that reads back to exactly the same double.
  OutputFile& real(double value);

  template <class T>
  OutputFile& raw(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    reserve(sizeof(T));
    std::memcpy(buffer_.data() + used_, &value, sizeof(T));
    used_ += sizeof(T);
    return *this;
  }
  OutputFile& bytes(const void* data, std::size_t size);

  /// Flushes and closes; throws RunError if anything failed. Must be called:
  /// the destructor only releases the handle.
  void close();

 private:
  void reserve(std::size_t size);
  void flush();

  std::string path_;
  std::FILE* file_ = nullptr;
  std::string buffer_;
  std::size_t used_ = 0;
};

}  // namespace mr::plugins::tet
