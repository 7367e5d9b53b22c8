#pragma once
// The readers and writers of this plugin, one pair per format. Readers parse
// a file's bytes and throw mr::InputError naming the file (`name`); writers
// throw mr::RunError.

#include <mr/core/triangle_soup.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace mr::plugins::stl_obj_off_ply {

TriangleSoup read_stl(std::string_view bytes, const std::string& name);
void write_stl(const TriangleSoup& soup, const std::filesystem::path& path, bool binary);

TriangleSoup read_obj(std::string_view bytes, const std::string& name);
/// `destination`: the file's final name, after which the MTL library and
/// textures are named (empty: materials are not written).
void write_obj(const TriangleSoup& soup, const std::filesystem::path& path,
               const std::filesystem::path& destination = {});

TriangleSoup read_off(std::string_view bytes, const std::string& name);
void write_off(const TriangleSoup& soup, const std::filesystem::path& path);

TriangleSoup read_ply(std::string_view bytes, const std::string& name);
void write_ply(const TriangleSoup& soup, const std::filesystem::path& path, bool binary);

/// Unit normal of a triangle by the right-hand rule; zero when it is degenerate.
Vec3d facet_normal(const Vec3d& a, const Vec3d& b, const Vec3d& c);

}  // namespace mr::plugins::stl_obj_off_ply
