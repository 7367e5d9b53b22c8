#pragma once
// A shared object of ours loaded at run time (dlopen) the first time one of
// its functions is needed, so that a run which never needs it does not load
// the libraries it links: loading OpenVDB costs a process 26 MB of resident
// memory and 30 ms (docs/ARCHITECTURE.md, Layers).

#include <filesystem>
#include <mutex>
#include <string>

namespace mr {

class PluginModule {
 public:
  /// `file_name` is looked for in <libdir>/meshrepair beside the running
  /// program's bin/, then at `build_path`, where the build put it.
  PluginModule(std::string file_name, std::filesystem::path build_path);
  PluginModule(const PluginModule&) = delete;
  PluginModule& operator=(const PluginModule&) = delete;

  /// The address of the module's exported symbol `name`, loading the module
  /// on first use (thread-safe). Throws RunError naming the paths tried when
  /// it cannot be loaded or lacks the symbol. The module is never unloaded:
  /// what its functions return may point into its code.
  void* symbol(const char* name);

 private:
  void load();

  std::string file_name_;
  std::filesystem::path build_path_;
  std::once_flag loaded_;
  void* handle_ = nullptr;
  std::string error_;
};

}  // namespace mr
