#include <mr/core/errors.h>
#include <mr/core/plugin_module.h>

#include <dlfcn.h>
#include <unistd.h>

#include <array>
#include <vector>

namespace mr {
namespace {

// The folder of the running program, or empty if /proc cannot tell.
std::filesystem::path program_folder() {
  std::array<char, 4096> path{};
  const ssize_t length = ::readlink("/proc/self/exe", path.data(), path.size() - 1);
  if (length <= 0) return {};
  return std::filesystem::path(std::string(path.data(), std::size_t(length))).parent_path();
}

}  // namespace

PluginModule::PluginModule(std::string file_name, std::filesystem::path build_path)
    : file_name_(std::move(file_name)), build_path_(std::move(build_path)) {}

void PluginModule::load() {
  std::vector<std::filesystem::path> candidates;
  if (const std::filesystem::path bin = program_folder(); !bin.empty())
    candidates.push_back(bin.parent_path() / MR_INSTALL_LIBDIR / "meshrepair" / file_name_);
  candidates.push_back(build_path_);
  std::string tried;
  for (const std::filesystem::path& path : candidates) {
    handle_ = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle_) return;
    tried += "\n  " + std::string(::dlerror());
  }
  error_ = "the plugin module " + file_name_ + " could not be loaded:" + tried;
}

void* PluginModule::symbol(const char* name) {
  std::call_once(loaded_, [this] { load(); });
  if (!handle_) throw RunError(error_);
  void* address = ::dlsym(handle_, name);
  if (!address) throw RunError("the plugin module " + file_name_ + " has no entry point " + name);
  return address;
}

}  // namespace mr
