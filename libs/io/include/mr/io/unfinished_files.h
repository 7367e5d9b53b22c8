#pragma once
// Files being written under a temporary name, so that a run stopped by a signal
// removes them before it ends. The list is process-wide because signal handlers
// are; it holds fixed slots read without locks, as a handler may only call
// async-signal-safe functions.

#include <filesystem>

namespace mr::io {

/// Registers `path` for removal on SIGINT, SIGTERM and SIGHUP while this object lives.
/// Registration is best effort: past a fixed number of files at once, a file is not listed.
class UnfinishedFile {
 public:
  explicit UnfinishedFile(const std::filesystem::path& path);
  ~UnfinishedFile();
  UnfinishedFile(const UnfinishedFile&) = delete;
  UnfinishedFile& operator=(const UnfinishedFile&) = delete;

 private:
  int slot_ = -1;
};

/// Unlinks every registered file. Async-signal-safe.
void remove_unfinished_files() noexcept;

/// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove the unfinished files,
/// then end the process by the same signal (so the exit status still tells which).
/// For a tool's main(); a library never installs handlers on its own.
void remove_unfinished_files_on_signals();

}  // namespace mr::io
