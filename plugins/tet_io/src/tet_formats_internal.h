#pragma once
// The readers and writers of the tet plugin, registered by tet_formats.cpp.
// Readers parse a file's bytes and throw mr::InputError naming the file (`name`).

#include <mr/core/tet_mesh.h>
#include <mr/io/options.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace mr::plugins::tet {

TetMesh read_msh(std::string_view bytes, const std::string& name);
void write_msh(const TetMesh& mesh, const std::filesystem::path& path, const io::WriteOptions& options);

TetMesh read_medit(std::string_view bytes, const std::string& name);
void write_medit(const TetMesh& mesh, const std::filesystem::path& path);

void write_vtu(const TetMesh& mesh, const std::filesystem::path& path, const io::WriteOptions& options);

}  // namespace mr::plugins::tet
