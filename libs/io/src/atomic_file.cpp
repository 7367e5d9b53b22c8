#include <mr/core/errors.h>
#include <mr/io/atomic_file.h>
#include <mr/io/unfinished_files.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>
#include <system_error>

#include <fcntl.h>
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

std::filesystem::path folder_of(const std::filesystem::path& destination) {
  return destination.has_parent_path() ? destination.parent_path() : std::filesystem::path(".");
}

// The path through which a process reaches one of its open files.
std::filesystem::path descriptor_path(int descriptor) {
  return std::filesystem::path("/proc/self/fd") / std::to_string(descriptor);
}

class Descriptor {
 public:
  explicit Descriptor(int descriptor) : descriptor_(descriptor) {}
  ~Descriptor() {
    if (descriptor_ >= 0) ::close(descriptor_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return descriptor_; }

 private:
  int descriptor_;
};

// Runs `write(path)`; a writer's error names `destination`, the file the user asked for, not `path`.
void write_naming_destination(const std::filesystem::path& path, const std::filesystem::path& destination,
                              const std::function<void(const std::filesystem::path&)>& write) {
  try {
    write(path);
  } catch (const RunError& e) {
    std::string message = e.what();
    const std::string written = path.string();
    for (std::size_t at = message.find(written); at != std::string::npos;
         at = message.find(written, at + destination.string().size()))
      message.replace(at, written.size(), destination.string());
    throw RunError(message);
  }
}

// Moves a complete file at `temp` over `destination` in one rename; removes `temp` if that fails.
void move_into_place(const std::filesystem::path& temp, const std::filesystem::path& destination) {
  std::error_code ec;
  std::filesystem::rename(temp, destination, ec);
  if (!ec) return;
  std::error_code ignored;
  std::filesystem::remove(temp, ignored);
  throw RunError("cannot move the output into place at " + destination.string() + ": " + ec.message());
}

// For filesystems without unnamed files: write under a hidden temporary name.
// A run stopped by a signal removes it; one killed outright may leave it behind.
void write_through_named_temporary(const std::filesystem::path& destination,
                                   const std::function<void(const std::filesystem::path&)>& write) {
  const std::filesystem::path temp = temporary_sibling(destination);
  const UnfinishedFile listed(temp);
  try {
    write_naming_destination(temp, destination, write);
    if (!std::filesystem::exists(temp))
      throw RunError("writing " + destination.string() + " produced no file");
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    throw;
  }
  move_into_place(temp, destination);
}

}  // namespace

void write_atomically(const std::filesystem::path& destination,
                      const std::function<void(const std::filesystem::path&)>& write) {
  // An unnamed file in the destination's folder (O_TMPFILE): until it is given a
  // name, a run killed at any moment, even by SIGKILL, leaves nothing behind.
  const Descriptor unnamed(::open(folder_of(destination).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666));
  if (unnamed.get() < 0) return write_through_named_temporary(destination, write);
  write_naming_destination(descriptor_path(unnamed.get()), destination, write);
  // Named only once complete: as the destination itself where there is none yet.
  if (::linkat(AT_FDCWD, descriptor_path(unnamed.get()).c_str(), AT_FDCWD, destination.c_str(),
               AT_SYMLINK_FOLLOW) == 0)
    return;
  // Else under a hidden name, then moved over the destination in one rename.
  // No call links a file over another, so a run killed outright (SIGKILL)
  // between these two calls leaves the complete new output under the hidden
  // name beside the previous one.
  const std::filesystem::path temp = temporary_sibling(destination);
  const UnfinishedFile listed(temp);
  if (::linkat(AT_FDCWD, descriptor_path(unnamed.get()).c_str(), AT_FDCWD, temp.c_str(), AT_SYMLINK_FOLLOW) !=
      0)
    throw RunError("cannot name the output " + destination.string() + ": " + std::strerror(errno));
  move_into_place(temp, destination);
}

}  // namespace mr::io
