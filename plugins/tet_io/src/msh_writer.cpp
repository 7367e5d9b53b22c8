// Gmsh MSH writer: 4.1 (default) or 2.2, ASCII or binary. Tets are element
// type 4 and triangles type 2; each element's label is both its physical tag
// and (when positive) its elementary/entity tag. Node tags are 1..N in order.
// Node fields (TetMesh::node_fields) follow as $NodeData sections.

#include "msh_layout.h"
#include "tet_formats_internal.h"

#include <mr/core/errors.h>
#include <mr/io/output_file.h>

#include <algorithm>
#include <limits>
#include <string>

namespace mr::plugins::tet {
namespace {

// Emits MSH values either as ASCII fields separated by spaces, one record a
// line, or as raw binary (size_t = uint64, int = int32, double).
class MshOutput {
 public:
  MshOutput(io::OutputFile& file, bool binary) : file_(file), binary_(binary) {}

  void size(std::uint64_t v) {
    binary_ ? void(file_.write_native(v)) : ascii_integer(static_cast<std::int64_t>(v));
  }
  void int32(std::int32_t v) { binary_ ? void(file_.write_native(v)) : ascii_integer(v); }
  void real(double v) {
    if (binary_) {
      file_.write_native(v);
    } else {
      separate();
      file_ << v;
    }
  }
  void end_line() {
    if (!binary_) file_ << "\n";
    line_start_ = true;
  }
  /// Section markers are text in both encodings; binary data ends with a newline.
  void begin_section(const char* name) { file_ << name << "\n"; }
  void end_section(const char* name) {
    if (binary_) file_ << "\n";
    file_ << name << "\n";
  }
  io::OutputFile& file() { return file_; }
  bool binary() const { return binary_; }

 private:
  void separate() {
    if (!line_start_) file_ << " ";
    line_start_ = false;
  }
  void ascii_integer(std::int64_t v) {
    separate();
    file_ << static_cast<std::int64_t>(v);
  }

  io::OutputFile& file_;
  bool binary_;
  bool line_start_ = true;
};

void write_header(MshOutput& out, const char* version) {
  out.file() << "$MeshFormat\n" << version << (out.binary() ? " 1 8\n" : " 0 8\n");
  if (out.binary()) {
    out.file().write_native(std::int32_t{1});
    out.file() << "\n";
  }
  out.file() << "$EndMeshFormat\n";
}

// Names of the tet labels written as physical tags, in text whatever the
// encoding (both versions). gmsh quotes names and has no escape: a double
// quote in a name becomes a single one.
void write_physical_names(MshOutput& out, const TetMesh& mesh, const MshDimension& volumes) {
  std::vector<std::pair<std::int32_t, std::string>> names;
  for (const MshEntity& entity : volumes.entities) {
    const auto it = mesh.tet_label_names.find(entity.label);
    if (entity.has_physical && it != mesh.tet_label_names.end()) names.emplace_back(entity.label, it->second);
  }
  if (names.empty()) return;
  out.file() << "$PhysicalNames\n" << std::to_string(names.size()) << "\n";
  for (auto& [label, name] : names) {
    std::replace(name.begin(), name.end(), '"', '\'');
    std::replace(name.begin(), name.end(), '\n', ' ');
    out.file() << "3 " << std::to_string(label) << " \"" << name << "\"\n";
  }
  out.file() << "$EndPhysicalNames\n";
}

// ---- MSH 4.1 ----

void write_entities(MshOutput& out, const MshDimension& dimension, const std::array<double, 6>& box) {
  for (const MshEntity& entity : dimension.entities) {
    out.int32(entity.tag);
    for (double v : box) out.real(v);
    out.size(entity.has_physical ? 1 : 0);
    if (entity.has_physical) out.int32(entity.label);
    out.size(0);  // no bounding entities
    out.end_line();
  }
}

void write_msh4_entities(MshOutput& out, const MshLayout& layout) {
  out.begin_section("$Entities");
  for (std::size_t count :
       {std::size_t(0), std::size_t(0), layout.surfaces.entities.size(), layout.volumes.entities.size()})
    out.size(count);
  out.end_line();
  write_entities(out, layout.surfaces, layout.bounding_box);
  write_entities(out, layout.volumes, layout.bounding_box);
  out.end_section("$EndEntities");
}

void write_msh4_nodes(MshOutput& out, const TetMesh& mesh, const MshLayout& layout) {
  const std::size_t n = mesh.positions.size();
  out.begin_section("$Nodes");
  for (std::size_t v : {std::size_t(n ? 1 : 0), n, std::size_t(n ? 1 : 0), n}) out.size(v);
  out.end_line();
  if (n) {
    out.int32(layout.node_entity_dim), out.int32(layout.node_entity_tag), out.int32(0), out.size(n);
    out.end_line();
    for (std::size_t i = 1; i <= n; ++i) out.size(i), out.end_line();
    if (out.binary()) {
      static_assert(sizeof(Vec3d) == 3 * sizeof(double));
      out.file().write_raw(mesh.positions.data(), n * sizeof(Vec3d));
    } else {
      for (const Vec3d& p : mesh.positions) out.real(p.x()), out.real(p.y()), out.real(p.z()), out.end_line();
    }
  }
  out.end_section("$EndNodes");
}

template <std::size_t N>
void write_msh4_blocks(MshOutput& out, const MshDimension& dimension,
                       const std::vector<std::array<Index, N>>& cells, int dim, int type,
                       std::size_t& next_tag) {
  for (const MshBlock& block : dimension.blocks) {
    out.int32(dim), out.int32(block.entity_tag), out.int32(type), out.size(block.end - block.begin);
    out.end_line();
    for (std::size_t c = block.begin; c < block.end; ++c) {
      out.size(next_tag++);
      for (Index v : cells[c]) out.size(std::uint64_t(v) + 1);
      out.end_line();
    }
  }
}

void write_msh4_elements(MshOutput& out, const TetMesh& mesh, const MshLayout& layout) {
  const std::size_t count = mesh.tets.size() + mesh.faces.size();
  out.begin_section("$Elements");
  out.size(layout.volumes.blocks.size() + layout.surfaces.blocks.size()), out.size(count);
  out.size(count ? 1 : 0), out.size(count);
  out.end_line();
  std::size_t next_tag = 1;
  write_msh4_blocks(out, layout.volumes, mesh.tets, 3, 4, next_tag);
  write_msh4_blocks(out, layout.surfaces, mesh.faces, 2, 2, next_tag);
  out.end_section("$EndElements");
}

// ---- MSH 2.2 ----

void check_int32_counts(const TetMesh& mesh, const std::filesystem::path& path) {
  constexpr std::size_t limit = std::numeric_limits<std::int32_t>::max();
  if (mesh.positions.size() >= limit || mesh.tets.size() + mesh.faces.size() >= limit)
    throw RunError("cannot write " + path.string() +
                   ": MSH 2.2 numbers nodes and elements with 32-bit ints; use 4.1");
}

void write_msh2_nodes(MshOutput& out, const TetMesh& mesh) {
  out.begin_section("$Nodes");
  out.file() << static_cast<std::int64_t>(mesh.positions.size()) << "\n";
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3d& p = mesh.positions[i];
    out.int32(static_cast<std::int32_t>(i + 1)), out.real(p.x()), out.real(p.y()), out.real(p.z());
    out.end_line();
  }
  out.end_section("$EndNodes");
}

// Every element carries two tags: physical (the label, 0 if the mesh has no
// labels) and elementary (the entity tag).
template <std::size_t N>
void write_msh2_cells(MshOutput& out, const MshDimension& dimension,
                      const std::vector<std::array<Index, N>>& cells, int type, std::int32_t& next_number) {
  if (cells.empty()) return;
  if (out.binary()) out.int32(type), out.int32(static_cast<std::int32_t>(cells.size())), out.int32(2);
  for (const MshBlock& block : dimension.blocks) {
    const std::int32_t physical = dimension.entities.front().has_physical ? block.label : 0;
    for (std::size_t c = block.begin; c < block.end; ++c) {
      out.int32(next_number++);
      if (!out.binary()) out.int32(type), out.int32(2);
      out.int32(physical), out.int32(block.entity_tag);
      for (Index v : cells[c]) out.int32(static_cast<std::int32_t>(v + 1));
      out.end_line();
    }
  }
}

void write_msh2_elements(MshOutput& out, const TetMesh& mesh, const MshLayout& layout) {
  out.begin_section("$Elements");
  out.file() << static_cast<std::int64_t>(mesh.tets.size() + mesh.faces.size()) << "\n";
  std::int32_t next_number = 1;
  write_msh2_cells(out, layout.volumes, mesh.tets, 4, next_number);
  write_msh2_cells(out, layout.surfaces, mesh.faces, 2, next_number);
  out.end_section("$EndElements");
}

// ---- both versions ----

// One $NodeData section per field: a time 0.0, step 0, one component, and
// a record (node tag, value) per node; the node tag is an int in both
// versions (as gmsh reads it).
void write_node_data(MshOutput& out, const TetMesh& mesh) {
  for (const auto& [name, values] : mesh.node_fields) {
    out.begin_section("$NodeData");
    std::string quoted = name;
    std::replace(quoted.begin(), quoted.end(), '"', '\'');
    std::replace(quoted.begin(), quoted.end(), '\n', ' ');
    out.file() << "1\n\"" << quoted << "\"\n1\n0\n3\n0\n1\n" << std::to_string(values.size()) << "\n";
    for (std::size_t i = 0; i < values.size(); ++i) {
      out.int32(static_cast<std::int32_t>(i + 1));
      out.real(values[i]);
      out.end_line();
    }
    out.end_section("$EndNodeData");
  }
}

}  // namespace

void write_msh(const TetMesh& mesh, const std::filesystem::path& path, const io::WriteOptions& options) {
  const bool v22 = options.msh_version == "2.2";
  if (!v22 && options.msh_version != "4.1")
    throw UsageError("unsupported MSH version '" + options.msh_version + "' (use 4.1 or 2.2)");
  if (v22) check_int32_counts(mesh, path);
  if (!mesh.node_fields.empty() &&
      mesh.positions.size() >= std::size_t(std::numeric_limits<std::int32_t>::max()))
    throw RunError("cannot write " + path.string() + ": node data numbers nodes with 32-bit ints");
  const MshLayout layout = make_msh_layout(mesh);
  io::OutputFile file(path);
  MshOutput out(file, options.binary);
  write_header(out, v22 ? "2.2" : "4.1");
  write_physical_names(out, mesh, layout.volumes);
  if (v22) {
    write_msh2_nodes(out, mesh);
    write_msh2_elements(out, mesh, layout);
  } else {
    write_msh4_entities(out, layout);
    write_msh4_nodes(out, mesh, layout);
    write_msh4_elements(out, mesh, layout);
  }
  write_node_data(out, mesh);
  file.close();
}

}  // namespace mr::plugins::tet
