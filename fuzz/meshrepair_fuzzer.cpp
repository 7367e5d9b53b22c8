// libFuzzer target for the whole meshrepair pipeline on tiny inputs (see
// meshrepair_entry.h). A run over a second on such an input is a finding
// too: it is reported on stderr, and the input saved in $MR_FUZZ_SLOW_DIR
// when that is set.

#include "meshrepair_entry.h"

#include <mr/io/default_registry.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>

namespace {

// Where the runs put their files: under $TMPDIR, removed at exit.
struct WorkDirectory {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("mr-fuzz-meshrepair-" + std::to_string(::getpid()));
  WorkDirectory() { std::filesystem::create_directories(path); }
  ~WorkDirectory() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

void save_slow_input(std::string_view bytes, double seconds) {
  const std::string hash = std::to_string(std::hash<std::string_view>()(bytes));
  std::fprintf(stderr, "MR_FUZZ_SLOW: meshrepair took %.2f s on a %zu-byte input (%s)\n", seconds,
               bytes.size(), hash.c_str());
  const char* dir = std::getenv("MR_FUZZ_SLOW_DIR");
  if (!dir) return;
  std::filesystem::create_directories(dir);
  std::ofstream(std::filesystem::path(dir) / ("slow-" + hash), std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mr::io::Registry registry = mr::io::make_default_registry();
  static const WorkDirectory dir;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const mr::fuzz::PipelineRun run = mr::fuzz::run_meshrepair(registry, bytes, dir.path);
  if (run.seconds > 1.0) save_slow_input(bytes, run.seconds);
  return 0;
}
