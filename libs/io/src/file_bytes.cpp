#include <mr/io/file_bytes.h>

#include <fstream>

namespace mr::io {

std::vector<char> read_file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "cannot open the file for reading");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError(path.string(), "cannot determine the file size");
  in.seekg(0, std::ios::beg);
  std::vector<char> bytes(static_cast<std::size_t>(size));
  if (size > 0 && !in.read(bytes.data(), size)) throw InputError(path.string(), "read error");
  return bytes;
}

void ByteReader::require(std::uint64_t count, std::uint64_t item_size, const char* what) const {
  const std::uint64_t left = remaining();
  if (item_size != 0 && count > left / item_size)
    fail(std::string("truncated: ") + what + " needs " + std::to_string(count) + " x " +
         std::to_string(item_size) + " bytes at offset " + std::to_string(pos_) + " but only " +
         std::to_string(left) + " remain");
}

std::string_view ByteReader::take(std::size_t count, const char* what) {
  require(count, 1, what);
  std::string_view view(data_ + pos_, count);
  pos_ += count;
  return view;
}

void ByteReader::seek(std::size_t position, const char* what) {
  if (position > size_)
    fail(std::string(what) + " points to offset " + std::to_string(position) + " past the end of the file (" +
         std::to_string(size_) + " bytes)");
  pos_ = position;
}

void ByteReader::fail(const std::string& problem) const { throw InputError(path_, problem); }

}  // namespace mr::io
