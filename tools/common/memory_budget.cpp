#include "memory_budget.h"

#include <mr/core/errors.h>

#include <string>
#include <system_error>

namespace mr::tools {
namespace {

std::string megabytes(std::size_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MB"; }

}  // namespace

void check_file_fits(const std::filesystem::path& path, std::size_t max_memory) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size <= max_memory) return;  // an unreadable file is the reader's to report
  throw InputError(path.string(), "the file is " + megabytes(size) + ", more than --max-memory " +
                                      megabytes(max_memory) + " allows; nothing was read");
}

void check_faces_fit(const std::filesystem::path& path, std::size_t faces, std::size_t bytes_per_face,
                     std::size_t max_memory) {
  if (faces <= max_memory / bytes_per_face) return;
  throw InputError(path.string(), std::to_string(faces) + " faces would need about " +
                                      megabytes(faces * bytes_per_face) + ", more than --max-memory " +
                                      megabytes(max_memory) + " allows");
}

}  // namespace mr::tools
