#include "output_file.h"

#include <mr/core/errors.h>

#include <cerrno>
#include <charconv>
#include <system_error>

namespace mr::plugins::tet {
namespace {

constexpr std::size_t kBufferSize = std::size_t(1) << 20;
constexpr std::size_t kLongestNumber = 32;  // "-1.2345678901234567e-308" and int64 fit

std::string reason() { return std::generic_category().message(errno); }

}  // namespace

OutputFile::OutputFile(const std::filesystem::path& path) : path_(path.string()), buffer_(kBufferSize, '\0') {
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) throw RunError("cannot open " + path_ + " for writing: " + reason());
}

OutputFile::~OutputFile() {
  if (file_) std::fclose(file_);
}

void OutputFile::flush() {
  if (used_ != 0 && std::fwrite(buffer_.data(), 1, used_, file_) != used_)
    throw RunError("cannot write to " + path_ + ": " + reason());
  used_ = 0;
}

void OutputFile::reserve(std::size_t size) {
  if (used_ + size > buffer_.size()) flush();
}

OutputFile& OutputFile::bytes(const void* data, std::size_t size) {
  if (size > buffer_.size()) {
    flush();
    if (std::fwrite(data, 1, size, file_) != size) throw RunError("cannot write to " + path_ + ": " + reason());
    return *this;
  }
  reserve(size);
  std::memcpy(buffer_.data() + used_, data, size);
  used_ += size;
  return *this;
}

OutputFile& OutputFile::text(std::string_view s) { return bytes(s.data(), s.size()); }

OutputFile& OutputFile::integer(std::int64_t value) {
  reserve(kLongestNumber);
  char* begin = buffer_.data() + used_;
  used_ += static_cast<std::size_t>(std::to_chars(begin, begin + kLongestNumber, value).ptr - begin);
  return *this;
}

OutputFile& OutputFile::real(double value) {
  reserve(kLongestNumber);
  char* begin = buffer_.data() + used_;
  used_ += static_cast<std::size_t>(std::to_chars(begin, begin + kLongestNumber, value).ptr - begin);
  return *this;
}

void OutputFile::close() {
  flush();
  std::FILE* file = file_;
  file_ = nullptr;
  if (std::fclose(file) != 0) throw RunError("cannot finish writing " + path_ + ": " + reason());
}

}  // namespace mr::plugins::tet
