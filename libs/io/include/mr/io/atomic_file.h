#pragma once
// Write-to-temporary-then-rename, so an output file is either complete or absent.

#include <filesystem>
#include <functional>

namespace mr::io {

/// Calls `write(temp_path)` with a fresh path in the destination's folder
/// that has the destination's extension, then renames it to `destination`.
/// If `write` throws, the temporary file is removed and the exception passes on;
/// `destination` is left untouched.
void write_atomically(const std::filesystem::path& destination,
                      const std::function<void(const std::filesystem::path&)>& write);

}  // namespace mr::io
