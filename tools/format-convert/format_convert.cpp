#include "format_convert.h"

#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <sstream>

namespace mr::tools {
namespace {

struct ConvertOptions {
  io::ReadOptions read;
  io::WriteOptions write;
};

std::string format_table(const io::Registry& registry) {
  std::ostringstream out;
  out << "Formats (chosen by extension; --from/--to override):\n";
  for (const io::Format& format : registry.formats()) {
    out << "  " << format.name << " (";
    for (std::size_t i = 0; i < format.extensions.size(); ++i)
      out << (i ? " " : "") << format.extensions[i];
    out << ") " << (format.kind == io::MeshKind::volume ? "volume" : "surface") << ", "
        << (format.can_read() ? "read" : "") << (format.can_read() && format.can_write() ? "/" : "")
        << (format.can_write() ? "write" : "") << ": " << format.description << "\n";
  }
  return out.str();
}

cli::ToolSpec make_spec(ConvertOptions& o, const io::Registry& registry) {
  using cli::parse_double;
  using cli::parse_int;
  cli::ToolSpec spec;
  spec.name = "format-convert";
  spec.summary = "Convert a mesh between formats: surface to surface, volume to volume, "
                 "or volume to surface (its boundary).";
  spec.positionals = {"IN", "OUT"};
  spec.description = format_table(registry);
  auto& w = o.write;
  spec.options = {
      {"--from", "", "FORMAT", "read IN as FORMAT whatever its extension",
       [&](const std::string& v) { o.read.format = v; }},
      {"--to", "", "FORMAT", "write OUT as FORMAT whatever its extension",
       [&](const std::string& v) { w.format = v; }},
      {"--ascii", "", "", "write the text variant of STL, PLY and MSH (default: binary)",
       [&](const std::string&) { w.binary = false; }},
      {"--msh-version", "", "V", "MSH version to write: 4.1 (default) or 2.2",
       [&](const std::string& v) {
         if (v != "4.1" && v != "2.2") throw UsageError("--msh-version must be 4.1 or 2.2");
         w.msh_version = v;
       }},
      {"--draco", "", "", "compress glTF/GLB meshes with KHR_draco_mesh_compression",
       [&](const std::string&) { w.draco.compress_gltf = true; }},
      {"--draco-position-bits", "", "N", "Draco position quantization bits (default 16)",
       [&](const std::string& v) { w.draco.position_bits = parse_int("--draco-position-bits", v, 1, 30); }},
      {"--draco-normal-bits", "", "N", "Draco normal quantization bits (default 10)",
       [&](const std::string& v) { w.draco.normal_bits = parse_int("--draco-normal-bits", v, 1, 30); }},
      {"--draco-uv-bits", "", "N", "Draco texture coordinate quantization bits (default 12)",
       [&](const std::string& v) { w.draco.uv_bits = parse_int("--draco-uv-bits", v, 1, 30); }},
      {"--draco-color-bits", "", "N", "Draco colour quantization bits (default 8)",
       [&](const std::string& v) { w.draco.color_bits = parse_int("--draco-color-bits", v, 1, 30); }},
      {"--draco-speed", "", "N", "Draco speed 0 (smallest) to 10 (fastest), default 3",
       [&](const std::string& v) { w.draco.speed = parse_int("--draco-speed", v, 0, 10); }},
      {"--voxel-size", "", "SIZE", "level set voxel size, absolute (default: bbox diagonal / 256)",
       [&](const std::string& v) { w.level_set.voxel_size = parse_double("--voxel-size", v); }},
      {"--half-width", "", "VOXELS", "level set narrow band half width in voxels (default 3)",
       [&](const std::string& v) { w.level_set.half_width = parse_double("--half-width", v); }},
      {"--isovalue", "", "VALUE", "level set to mesh: the level to extract (default 0)",
       [&](const std::string& v) { o.read.level_set.isovalue = parse_double("--isovalue", v); }},
      {"--adaptivity", "", "A", "level set to mesh: 0 uniform (default) to 1 most simplified",
       [&](const std::string& v) { o.read.level_set.adaptivity = parse_double("--adaptivity", v); }},
  };
  return spec;
}

void convert(const io::Registry& registry, const std::string& in, const std::string& out,
             const ConvertOptions& o) {
  const bool volume_in = io::is_volume_format(registry, in, o.read.format);
  const bool volume_out = registry.resolve_for_write(out, o.write.format).kind == io::MeshKind::volume;
  if (volume_out && !volume_in)
    throw UsageError("cannot write the surface " + in + " as a volume mesh: use tetrahedralize");
  if (volume_out) {
    io::write_volume(registry, io::read_volume(registry, in, o.read), out, o.write);
    return;
  }
  io::write_surface(registry, io::read_surface(registry, in, o.read), out, o.write);
}

}  // namespace

int format_convert(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const io::Registry registry = io::make_default_registry();
  ConvertOptions options;
  const cli::ToolSpec spec = make_spec(options, registry);
  return cli::run_tool(spec, args, out, err, [&](const std::vector<std::string>& files) {
    convert(registry, files[0], files[1], options);
  });
}

}  // namespace mr::tools
