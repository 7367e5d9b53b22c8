#include "lazy_vdb_formats.h"

#include <mr/core/errors.h>
#include <mr/plugins/vdb_formats.h>

#include <dlfcn.h>
#include <unistd.h>

#include <array>
#include <memory>
#include <mutex>
#include <vector>

namespace mr::plugins {
namespace {

// Where the module may be: next to an installed tool (bin/../lib/meshrepair),
// then where this build put it.
std::vector<std::filesystem::path> module_candidates() {
  std::vector<std::filesystem::path> candidates;
  std::array<char, 4096> exe{};
  const ssize_t length = ::readlink("/proc/self/exe", exe.data(), exe.size() - 1);
  if (length > 0) {
    const std::filesystem::path bin =
        std::filesystem::path(std::string(exe.data(), std::size_t(length))).parent_path();
    candidates.push_back(bin.parent_path() / MR_INSTALL_LIBDIR / "meshrepair" / "libmr_vdb_io.so");
  }
  candidates.emplace_back(MR_VDB_MODULE_BUILD_PATH);
  return candidates;
}

// The module's own registry, loaded once and kept for the life of the
// process: the module is never unloaded, because the functions it
// registered point into its code.
class VdbModule {
 public:
  const io::Format& format() {
    std::call_once(loaded_, [this] { load(); });
    if (!format_) throw RunError(error_);
    return *format_;
  }

 private:
  void load() {
    std::string tried;
    for (const std::filesystem::path& path : module_candidates()) {
      void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        tried += "\n  " + path.string() + ": " + ::dlerror();
        continue;
      }
      const auto entry =
          reinterpret_cast<void (*)(io::Registry*)>(::dlsym(handle, "mr_register_vdb_formats"));
      if (!entry) {
        tried += "\n  " + path.string() + ": no entry point mr_register_vdb_formats";
        continue;
      }
      entry(&registry_);
      format_ = registry_.by_name("vdb");
      if (format_) return;
      tried += "\n  " + path.string() + ": registered no format \"vdb\"";
    }
    error_ =
        "the OpenVDB plugin module (libmr_vdb_io.so), which reads and writes .vdb files, could not be "
        "loaded:" +
        tried;
  }

  std::once_flag loaded_;
  io::Registry registry_;
  const io::Format* format_ = nullptr;
  std::string error_;
};

}  // namespace

void register_vdb_formats_lazily(io::Registry& registry) {
  auto module = std::make_shared<VdbModule>();
  io::Format format = vdb_format_declaration();
  format.read_surface_bytes = [module](std::string_view bytes, const std::string& name,
                                       const io::ReadOptions& options) {
    return module->format().read_surface_bytes(bytes, name, options);
  };
  format.write_surface = [module](const TriangleSoup& soup, const std::filesystem::path& path,
                                  const io::WriteOptions& options) {
    module->format().write_surface(soup, path, options);
  };
  format.read_field = [module](const std::filesystem::path& path) {
    return module->format().read_field(path);
  };
  registry.add(std::move(format));
}

}  // namespace mr::plugins
