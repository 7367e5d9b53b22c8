#pragma once
// Write-to-temporary-then-rename, so an output file is either complete or absent,
// even when the run is killed while writing.

#include <filesystem>
#include <functional>

namespace mr::io {

/// Calls `write(path)` with a path to a new, unnamed file in the destination's
/// folder (it has no extension: the writer must not choose a format by it), then
/// names the finished file and renames it to `destination`, so that `destination`
/// is either the complete new file or whatever was there before. If `write`
/// throws, the exception passes on and no file is left behind.
void write_atomically(const std::filesystem::path& destination,
                      const std::function<void(const std::filesystem::path&)>& write);

}  // namespace mr::io
