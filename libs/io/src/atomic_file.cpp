#include <mr/core/errors.h>
#include <mr/io/atomic_file.h>

#include <atomic>
#include <chrono>
#include <system_error>

#include <unistd.h>

namespace mr::io {
namespace {

// A name unique across processes (pid) and calls within one (counter).
std::filesystem::path temporary_sibling(const std::filesystem::path& destination) {
  static std::atomic<unsigned> counter{0};
  const auto tick = std::chrono::steady_clock::now().time_since_epoch().count();
  std::string name(".");
  name += destination.stem().string();
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
  for (const std::string& piece :
       {std::string(".tmp"), std::to_string(::getpid()), std::string("-"), std::to_string(counter++),
        std::string("-"), std::to_string(tick % 100000)})
    name += piece;
  name += destination.extension().string();
  return destination.parent_path() / name;
}

}  // namespace

void write_atomically(const std::filesystem::path& destination,
                      const std::function<void(const std::filesystem::path&)>& write) {
  const std::filesystem::path temp = temporary_sibling(destination);
  std::error_code ignored;
  try {
    write(temp);
    if (!std::filesystem::exists(temp))
      throw RunError("writing " + destination.string() + " produced no file");
    std::error_code ec;
    std::filesystem::rename(temp, destination, ec);
    if (ec)
      throw RunError("cannot move the output into place at " + destination.string() + ": " + ec.message());
  } catch (...) {
    std::filesystem::remove(temp, ignored);
    throw;
  }
}

}  // namespace mr::io
