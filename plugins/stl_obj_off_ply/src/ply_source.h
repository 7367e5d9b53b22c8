#pragma once
// Typed values from a PLY body, ASCII or binary (either byte order). Both
// sources check a count read from the file against the bytes left before the
// reader loops or allocates for it, and throw InputError naming the file.

#include "ply_header.h"

#include <mr/io/file_bytes.h>

#include <cstdint>
#include <string>

namespace mr::plugins::stl_obj_off_ply {

class PlyBinarySource {
 public:
  PlyBinarySource(std::string path, const char* data, std::size_t size, bool big_endian)
      : reader_(std::move(path), data, size), swap_(big_endian) {}

  /// Throws unless `element.count` entries of at least their minimum size fit.
  void check_count(const PlyElement& element) const;
  double number(PlyType type);
  std::int64_t integer(PlyType type);
  /// Reads a list's length and checks that its items fit in what remains.
  std::int64_t list_count(const PlyProperty& property);
  void skip(PlyType type, std::int64_t count);
  [[noreturn]] void fail(const std::string& problem) const { reader_.fail(problem); }

 private:
  template <class T>
  T raw(const char* what);
  /// Reads one value stored as `type` and returns it converted to `Result`.
  template <class Result>
  Result read_as(PlyType type);

  io::ByteReader reader_;
  bool swap_;
};

class PlyAsciiSource {
 public:
  PlyAsciiSource(std::string path, const char* data, std::size_t size)
      : path_(std::move(path)), data_(data), size_(size) {}

  void check_count(const PlyElement& element) const;
  double number(PlyType type);
  std::int64_t integer(PlyType type);
  std::int64_t list_count(const PlyProperty& property);
  void skip(PlyType type, std::int64_t count);
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  std::string_view token();

  std::string path_;
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace mr::plugins::stl_obj_off_ply
