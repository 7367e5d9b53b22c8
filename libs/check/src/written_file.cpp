#include <mr/check/written_file.h>

#include <mr/core/errors.h>

#include <chrono>

namespace mr::check {

io::WrittenFileCheck watertight_file_check(const io::Registry& registry,
                                           const std::filesystem::path& destination,
                                           WrittenFileReport* report) {
  return [&registry, destination, report](const std::filesystem::path& written) {
    const auto start = std::chrono::steady_clock::now();
    // The written file's own name may have no extension (see io::write_atomically).
    io::ReadOptions as_destination;
    as_destination.format = registry.resolve_for_read(destination, "").name;
    const SurfaceReport surface = check_surface(io::read_surface(registry, written, as_destination));
    if (report) {
      report->surface = surface;
      report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    if (const std::string failures = watertight_failures(surface); !failures.empty())
      throw RunError(destination.string() + ": the surface as written is not watertight (" + failures +
                     "); nothing was written");
  };
}

}  // namespace mr::check
