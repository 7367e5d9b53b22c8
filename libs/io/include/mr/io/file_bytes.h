#pragma once
// Bounds-checked access to a file's bytes, for readers of binary formats.
// Every read past the end throws InputError naming the file, so a count read
// from a header can never make a reader run past the data or allocate for it.

#include <mr/core/errors.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace mr::io {

/// The whole file in memory; throws InputError if it cannot be opened or read.
std::vector<char> read_file_bytes(const std::filesystem::path& path);

class ByteReader {
 public:
  ByteReader(std::string path, const char* data, std::size_t size)
      : path_(std::move(path)), data_(data), size_(size) {}

  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return size_ - pos_; }
  bool at_end() const { return pos_ == size_; }
  const std::string& path() const { return path_; }

  /// Throws unless `count` items of `item_size` bytes remain. Call it before
  /// allocating for a count read from the file.
  void require(std::uint64_t count, std::uint64_t item_size, const char* what) const;

  template <class T>
  T read(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    require(1, sizeof(T), what);
    T value;
    std::memcpy(&value, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }

  /// Returns a view of the next `count` bytes and skips them.
  std::string_view take(std::size_t count, const char* what);
  void skip(std::size_t count, const char* what) { take(count, what); }
  void seek(std::size_t position, const char* what);

  [[noreturn]] void fail(const std::string& problem) const;

 private:
  std::string path_;
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace mr::io
