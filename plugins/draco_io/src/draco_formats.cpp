// The .drc format: one Draco-compressed triangle mesh, with face regions kept
// in a GENERIC attribute (see draco_codec_detail.h).

#include <mr/plugins/draco_formats.h>

#include "draco_codec_detail.h"

#include <mr/io/output_file.h>

namespace mr::plugins {
namespace {

TriangleSoup read_drc(std::string_view bytes, const std::string& name, const io::ReadOptions&) {
  return detail::decode_draco_mesh(bytes, name, {}, true);
}

void write_drc(const TriangleSoup& soup, const std::filesystem::path& path, const io::WriteOptions& options) {
  const DracoEncoded encoded = detail::encode_draco_mesh(soup, options.draco, true);
  io::write_file_bytes(path, {encoded.bytes.data(), encoded.bytes.size()});
}

}  // namespace

void register_draco_formats(io::Registry& registry) {
  io::Format drc;
  drc.name = "drc";
  drc.extensions = {".drc"};
  drc.kind = io::MeshKind::surface;
  drc.description =
      "Google Draco compressed mesh (normals, uvs, colours and face regions kept; "
      "positions quantized, see --draco-position-bits)";
  drc.read_surface_bytes = read_drc;
  drc.write_surface = write_drc;
  drc.position_grid = [](const io::WriteOptions& options, const Vec3d& lo, const Vec3d& hi) {
    return io::draco_position_grid(options.draco, lo, hi);
  };
  registry.add(std::move(drc));
}

}  // namespace mr::plugins
