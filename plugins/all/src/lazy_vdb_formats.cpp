#include "lazy_vdb_formats.h"

#include <mr/core/errors.h>
#include <mr/core/plugin_module.h>
#include <mr/plugins/vdb_formats.h>

#include <memory>
#include <mutex>

namespace mr::plugins {
namespace {

// The module's own registry, filled on first use.
class VdbModule {
 public:
  const io::Format& format() {
    std::call_once(registered_, [this] {
      const auto entry = reinterpret_cast<void (*)(io::Registry*)>(module_.symbol("mr_register_vdb_formats"));
      entry(&registry_);
      format_ = registry_.by_name("vdb");
    });
    if (!format_) throw RunError("the plugin module libmr_vdb_io.so registered no format \"vdb\"");
    return *format_;
  }

 private:
  PluginModule module_{"libmr_vdb_io.so", MR_VDB_MODULE_BUILD_PATH};
  std::once_flag registered_;
  io::Registry registry_;
  const io::Format* format_ = nullptr;
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
