#pragma once
// What the tools that build a solid from a surface require of their input
// beyond being readable.

#include <mr/core/triangle_soup.h>

#include <filesystem>

namespace mr::tools {

/// InputError naming `path` unless some triangle has non-zero area (its
/// corners not collinear, decided exactly): points and segments bound no solid.
void check_has_area(const std::filesystem::path& path, const TriangleSoup& input);

}  // namespace mr::tools
