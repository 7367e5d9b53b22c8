#include <mr/io/output_file.h>

#include <mr/core/errors.h>

#include <cerrno>
#include <charconv>

namespace mr::io {
namespace {

constexpr std::size_t kLongestNumber = 32;  // "-1.2345678901234567e-308" and any int64 fit

std::string errno_text() { return errno ? std::string(": ") + std::strerror(errno) : std::string(); }

}  // namespace

OutputFile::OutputFile(const std::filesystem::path& path) : path_(path.string()), buffer_(kBufferSize, '\0') {
  errno = 0;
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) fail("cannot open " + path_ + " for writing");
}

OutputFile::~OutputFile() {
  if (file_) std::fclose(file_);
}

void OutputFile::fail(const std::string& action) const { throw RunError(action + errno_text()); }

void OutputFile::write_past_buffer(const void* data, std::size_t size) {
  flush();
  if (size < kBufferSize) {
    std::memcpy(buffer_.data(), data, size);
    used_ = size;
    return;
  }
  // A block at least as large as the buffer skips it.
  errno = 0;
  if (std::fwrite(data, 1, size, file_) != size) fail("cannot write to " + path_);
}

void OutputFile::flush() {
  if (used_ == 0) return;
  errno = 0;
  if (std::fwrite(buffer_.data(), 1, used_, file_) != used_) fail("cannot write to " + path_);
  used_ = 0;
}

void OutputFile::close() {
  flush();
  errno = 0;
  const bool failed = std::fflush(file_) != 0 || std::ferror(file_) != 0;
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed || close_failed) fail("cannot write to " + path_);
}

template <class T>
OutputFile& OutputFile::write_number(T value) {
  if (kBufferSize - used_ < kLongestNumber) flush();
  char* begin = buffer_.data() + used_;
  used_ += static_cast<std::size_t>(std::to_chars(begin, begin + kLongestNumber, value).ptr - begin);
  return *this;
}

OutputFile& OutputFile::operator<<(double value) { return write_number(value); }
OutputFile& OutputFile::operator<<(float value) { return write_number(value); }
OutputFile& OutputFile::operator<<(std::int64_t value) { return write_number(value); }

void write_file_bytes(const std::filesystem::path& path, std::string_view bytes) {
  OutputFile out(path);
  out.write_raw(bytes.data(), bytes.size());
  out.close();
}

}  // namespace mr::io
