#pragma once
// The readers and writers of the tet plugin, registered by tet_formats.cpp.

#include <mr/core/tet_mesh.h>
#include <mr/io/options.h>

#include <filesystem>

namespace mr::plugins::tet {

TetMesh read_msh(const std::filesystem::path& path);
void write_msh(const TetMesh& mesh, const std::filesystem::path& path, const io::WriteOptions& options);

TetMesh read_medit(const std::filesystem::path& path);
void write_medit(const TetMesh& mesh, const std::filesystem::path& path);

void write_vtu(const TetMesh& mesh, const std::filesystem::path& path, const io::WriteOptions& options);

}  // namespace mr::plugins::tet
