#pragma once
// The check every tool that promises a watertight surface runs on the file
// it wrote: the file is read back, so the positions are the ones a user
// gets (float32 in STL and GLB, Draco's grid), welded by position and
// checked exactly (check_surface).

#include <mr/check/surface_check.h>
#include <mr/io/mesh_io.h>

#include <filesystem>

namespace mr::check {

struct WrittenFileReport {
  SurfaceReport surface;  ///< of the file as written
  double seconds = 0.0;   ///< reading it back and checking it
};

/// A check for io::write_surface: reads the written file back and throws
/// mr::RunError naming `destination` and what fails unless it is
/// watertight; fills `report` (if not null) either way.
io::WrittenFileCheck watertight_file_check(const io::Registry& registry,
                                           const std::filesystem::path& destination,
                                           WrittenFileReport* report = nullptr);

}  // namespace mr::check
