#include "format_convert.h"
#include "surface_output.h"

#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/io/text_encoding.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <ostream>
#include <sstream>

namespace mr::tools {
namespace {

struct ConvertOptions {
  io::ReadOptions read;
  io::WriteOptions write;
  std::string stats_path;
  int threads = 0;
  bool quiet = false;
  bool verbose = false;
  bool draco_bits_given = false;  ///< else a finer Draco grid may be taken to keep a surface watertight
};

// What was converted, for -v and --stats.
struct ConvertReport {
  bool volume = false;
  std::size_t vertices = 0;
  std::size_t elements = 0;  // tets of a volume, triangles of a surface
  double seconds_read = 0.0;
  double seconds_write = 0.0;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format_table(const io::Registry& registry) {
  std::ostringstream out;
  out << "Formats (chosen by extension; --from/--to override):\n";
  for (const io::Format& format : registry.formats()) {
    out << "  " << format.name << " (";
    for (std::size_t i = 0; i < format.extensions.size(); ++i) out << (i ? " " : "") << format.extensions[i];
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
  spec.summary =
      "Convert a mesh between formats: surface to surface, volume to volume, "
      "or volume to surface (its boundary).";
  spec.positionals = {"IN", "OUT"};
  spec.description = format_table(registry);
  auto& w = o.write;
  spec.options = {
      {"--from", "", "FORMAT", "read IN as FORMAT whatever its extension",
       [&](const std::string& v) { o.read.format = v; }},
      {"--to", "", "FORMAT", "write OUT as FORMAT whatever its extension",
       [&](const std::string& v) { w.format = v; }},
      cli::ascii_option(w.binary),
      {"--msh-version", "", "V", "MSH version to write: 4.1 (default) or 2.2",
       [&](const std::string& v) {
         if (v != "4.1" && v != "2.2") throw UsageError("--msh-version must be 4.1 or 2.2");
         w.msh_version = v;
       }},
      {"--draco", "", "", "compress glTF/GLB meshes with KHR_draco_mesh_compression",
       [&](const std::string&) { w.draco.compress_gltf = true; }},
      {"--draco-position-bits", "", "N", "Draco position quantization bits (default 16)",
       [&](const std::string& v) {
         w.draco.position_bits = parse_int("--draco-position-bits", v, 1, 30);
         o.draco_bits_given = true;
       }},
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
      cli::stats_option(o.stats_path, "write counts and seconds of reading and writing as JSON"),
      cli::threads_option(o.threads),
      cli::quiet_option(o.quiet),
      cli::verbose_option(o.verbose, "print what was read and written, and names that were not UTF-8"),
  };
  return spec;
}

// Names that are not UTF-8 are written decoded as Windows-1252 (io::as_utf8);
// with -v the tool says which.
void note_names_not_utf8(const TriangleSoup& soup, const std::string& in, std::ostream& err) {
  for (std::size_t r = 0; r < soup.region_names.size(); ++r)
    if (!io::is_utf8(soup.region_names[r]))
      err << "format-convert: " << in << ": region name " << r
          << " is not UTF-8; taken as Windows-1252: " << io::as_utf8(soup.region_names[r]) << "\n";
}

ConvertReport convert(const io::Registry& registry, const std::string& in, const std::string& out,
                      const ConvertOptions& o, std::ostream& err) {
  const bool volume_in = io::is_volume_format(registry, in, o.read.format);
  const bool volume_out = registry.resolve_for_write(out, o.write.format).kind == io::MeshKind::volume;
  if (volume_out && !volume_in)
    throw UsageError("cannot write the surface " + in + " as a volume mesh: use tetrahedralize");
  ConvertReport report;
  report.volume = volume_out;
  auto start = std::chrono::steady_clock::now();
  if (volume_out) {
    const TetMesh mesh = io::read_volume(registry, in, o.read);
    report.seconds_read = seconds_since(start);
    report.vertices = mesh.positions.size();
    report.elements = mesh.tets.size();
    start = std::chrono::steady_clock::now();
    io::write_volume(registry, mesh, out, o.write);
  } else {
    const TriangleSoup soup = io::read_surface(registry, in, o.read);
    report.seconds_read = seconds_since(start);
    report.vertices = soup.positions.size();
    report.elements = soup.triangles.size();
    if (o.verbose && !o.quiet) note_names_not_utf8(soup, in, err);
    start = std::chrono::steady_clock::now();
    write_surface_keeping_watertight(registry, soup, out, o.write, !o.draco_bits_given);
  }
  report.seconds_write = seconds_since(start);
  return report;
}

nlohmann::json make_stats(const std::string& in, const std::string& out, const ConvertReport& r) {
  return {{"input", io::as_utf8(in)},
          {"output", io::as_utf8(out)},
          {"kind", r.volume ? "volume" : "surface"},
          {"vertices", r.vertices},
          {r.volume ? "tets" : "faces", r.elements},
          {"seconds", {{"read", r.seconds_read}, {"write", r.seconds_write}}}};
}

}  // namespace

int format_convert(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const io::Registry registry = io::make_default_registry();
  ConvertOptions options;
  const cli::ToolSpec spec = make_spec(options, registry);
  return cli::run_tool(spec, args, out, err, [&](const std::vector<std::string>& files) {
    cli::run_with_threads(options.threads, [&] {
      const ConvertReport report = convert(registry, files[0], files[1], options, err);
      if (!options.stats_path.empty())
        cli::write_stats_file(options.stats_path, make_stats(files[0], files[1], report).dump(2));
      if (options.verbose && !options.quiet)
        out << files[0] << " -> " << files[1] << ": " << report.vertices << " vertices, " << report.elements
            << (report.volume ? " tets" : " faces") << " (read " << report.seconds_read << " s, write "
            << report.seconds_write << " s)\n";
    });
  });
}

}  // namespace mr::tools
