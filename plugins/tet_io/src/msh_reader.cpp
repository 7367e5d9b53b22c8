// Gmsh MSH reader: versions 2.x and 4.1, ASCII and binary. Sections other
// than $MeshFormat, $Entities, $PhysicalNames, $Nodes, $Elements and
// $NodeData are skipped.

#include "msh_sections.h"
#include "tet_formats_internal.h"

#include <string>

namespace mr::plugins::tet {
namespace {

struct MshHeader {
  int major = 0;
  MshEncoding encoding;
};

// Reads the int 1 that follows the header line of a binary file, which tells
// whether the file's byte order is ours.
void read_endianness(io::TextCursor& cursor, MshEncoding& encoding) {
  cursor.skip_line();
  const std::uint32_t one = cursor.raw<std::uint32_t>("endianness check");
  if (one == 1) return;
  if (one != 0x01000000u) cursor.fail("corrupt binary header: the endianness check is not 1");
  encoding.swap_bytes = true;
}

MshHeader read_header(io::TextCursor& cursor) {
  if (cursor.token_or_empty() != "$MeshFormat")
    cursor.fail("not a Gmsh MSH file (it does not start with $MeshFormat)");
  const std::string version(cursor.token("MSH version"));
  MshHeader header;
  if (version == "4.1") {
    header.major = 4;
  } else if (version == "2" || version == "2.0" || version == "2.1" || version == "2.2") {
    header.major = 2;
  } else {
    cursor.fail("unsupported MSH version " + version.substr(0, 20) + " (supported: 2.2 and 4.1)");
  }
  const std::uint64_t file_type = cursor.unsigned_integer("file type");
  const std::uint64_t data_size = cursor.unsigned_integer("data size");
  if (file_type > 1)
    cursor.fail("unknown file type " + std::to_string(file_type) + " (0 = ASCII, 1 = binary)");
  header.encoding.binary = file_type == 1;
  if (header.encoding.binary) {
    const bool supported = data_size == 8 || (header.major == 4 && data_size == 4);
    if (!supported) cursor.fail("unsupported data size " + std::to_string(data_size));
    header.encoding.size_t_bytes = static_cast<int>(data_size);
    read_endianness(cursor, header.encoding);
  }
  cursor.expect("$EndMeshFormat");
  return header;
}

class MshReader {
 public:
  MshReader(const std::string& path, std::string_view bytes) : cursor_(path, bytes) {}

  TetMesh read() {
    header_ = read_header(cursor_);
    while (!cursor_.at_end()) read_section();
    return assemble_tet_mesh(std::move(content_), cursor_.path());
  }

 private:
  void read_section() {
    const std::string name(cursor_.token("section name"));
    if (name.size() < 2 || name[0] != '$')
      cursor_.fail("expected a section such as $Nodes, found '" + name.substr(0, 40) + "'");
    const std::string end = "$End" + name.substr(1);
    if (!read_known_section(name)) {
      if (!cursor_.skip_past(end)) cursor_.fail("section " + name + " has no " + end);
      return;
    }
    cursor_.expect(end);
  }

  // Reads the body of a section this reader understands; false for others.
  bool read_known_section(const std::string& name) {
    const bool v4 = header_.major == 4;
    const MshEncoding& encoding = header_.encoding;
    // In binary MSH 4 the body starts on the line after the name.
    if (v4 && encoding.binary && (name == "$Entities" || name == "$Nodes" || name == "$Elements"))
      cursor_.skip_line();
    if (v4 && name == "$Entities") {
      read_msh4_entities(cursor_, encoding, labels_);
    } else if (name == "$PhysicalNames") {
      read_physical_names();
    } else if (name == "$Nodes") {
      v4 ? read_msh4_nodes(cursor_, encoding, content_) : read_msh2_nodes(cursor_, encoding, content_);
    } else if (name == "$Elements") {
      v4 ? read_msh4_elements(cursor_, encoding, labels_, content_)
         : read_msh2_elements(cursor_, encoding, content_);
    } else if (name == "$NodeData") {
      read_msh_node_data(cursor_, encoding, content_);
    } else {
      return false;
    }
    return true;
  }

  // Lines `dim tag "name"` (text in every encoding); names of volumes
  // (dim 3) become tet label names.
  void read_physical_names() {
    const std::uint64_t count = cursor_.unsigned_integer("number of physical names");
    cursor_.require(count, 6, "physical names");
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::int32_t dim = cursor_.int32("physical dimension");
      const std::int32_t tag = cursor_.int32("physical tag");
      std::string_view line;
      cursor_.next_line(line);
      const std::size_t open = line.find('"'), close = line.rfind('"');
      if (open == std::string_view::npos || close == open) cursor_.fail("a physical name is not quoted");
      if (dim == 3) content_.tet_label_names[tag] = std::string(line.substr(open + 1, close - open - 1));
    }
  }

  io::TextCursor cursor_;
  MshHeader header_;
  EntityLabels labels_;
  MshContent content_;
};

}  // namespace

TetMesh read_msh(std::string_view bytes, const std::string& name) { return MshReader(name, bytes).read(); }

}  // namespace mr::plugins::tet
