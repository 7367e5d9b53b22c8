#pragma once
// --max-memory: an input whose run would need more memory than allowed is
// refused with exit 2 before the run allocates for it, not killed halfway.

#include <cstddef>
#include <filesystem>

namespace mr::tools {

/// Peak memory of the tetrahedralization pipeline per input face, measured on
/// large soups (bench/README.md, "Large inputs"): 0.95 KB at 1.15M faces, more on smaller ones.
/// Kept below the measurements, so that only inputs certain not to fit are refused.
inline constexpr std::size_t kPipelineBytesPerFace = 768;

/// InputError naming `path` when the file alone is larger than `max_memory` bytes.
void check_file_fits(const std::filesystem::path& path, std::size_t max_memory);

/// InputError naming `path` when `faces` input faces would need more than
/// `max_memory` bytes at `bytes_per_face`.
void check_faces_fit(const std::filesystem::path& path, std::size_t faces, std::size_t bytes_per_face,
                     std::size_t max_memory);

}  // namespace mr::tools
