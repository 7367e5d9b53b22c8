#include "output_file.h"

#include <bit>
#include <cerrno>
#include <charconv>

namespace mr::plugins::stl_obj_off_ply {
namespace {

static_assert(std::endian::native == std::endian::little, "the binary writers assume a little-endian host");

constexpr std::size_t kFlushSize = 1 << 20;

std::string errno_text() { return errno ? std::string(": ") + std::strerror(errno) : std::string(); }

}  // namespace

OutputFile::OutputFile(const std::filesystem::path& path) : path_(path.string()) {
  errno = 0;
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) throw RunError("cannot open " + path_ + " for writing" + errno_text());
  buffer_.reserve(kFlushSize + 4096);
}

OutputFile::~OutputFile() {
  if (file_) std::fclose(file_);
}

void OutputFile::append(const char* data, std::size_t size) {
  buffer_.append(data, size);
  if (buffer_.size() >= kFlushSize) flush();
}

void OutputFile::flush() {
  if (buffer_.empty()) return;
  errno = 0;
  if (std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size())
    throw RunError("cannot write to " + path_ + errno_text());
  buffer_.clear();
}

void OutputFile::close() {
  flush();
  errno = 0;
  const bool failed = std::fflush(file_) != 0 || std::ferror(file_) != 0;
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed || close_failed) throw RunError("cannot write to " + path_ + errno_text());
}

OutputFile& OutputFile::operator<<(std::string_view text) {
  append(text.data(), text.size());
  return *this;
}

OutputFile& OutputFile::operator<<(char c) {
  append(&c, 1);
  return *this;
}

OutputFile& OutputFile::operator<<(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  append(text, static_cast<std::size_t>(result.ptr - text));
  return *this;
}

OutputFile& OutputFile::operator<<(float value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  append(text, static_cast<std::size_t>(result.ptr - text));
  return *this;
}

OutputFile& OutputFile::operator<<(std::int64_t value) {
  char text[24];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  append(text, static_cast<std::size_t>(result.ptr - text));
  return *this;
}

}  // namespace mr::plugins::stl_obj_off_ply
