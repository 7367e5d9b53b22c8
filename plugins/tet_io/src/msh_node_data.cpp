// MSH $NodeData (the same in 2.2 and 4.1): string, real and integer tags in
// text, then one record per node, a node tag and its components. Only the
// name (first string tag) and the values of one-component fields are kept;
// the sizing fields of fTetWild and gmsh's background meshes are such.

#include "msh_sections.h"

#include <string>

namespace mr::plugins::tet {
namespace {

// The text of a string tag: the line without its surrounding quotes.
std::string unquoted(std::string_view line) {
  const std::size_t open = line.find('"'), close = line.rfind('"');
  if (open == std::string_view::npos || close == open) return std::string(line);
  return std::string(line.substr(open + 1, close - open - 1));
}

std::string read_name(io::TextCursor& cursor) {
  const std::uint64_t count = cursor.unsigned_integer("number of string tags");
  cursor.require(count, 2, "$NodeData string tags");
  cursor.skip_line();
  std::string name;
  for (std::uint64_t i = 0; i < count; ++i) {
    std::string_view line;
    if (!cursor.next_line(line)) cursor.fail("$NodeData ends inside its string tags");
    if (i == 0) name = unquoted(line);
  }
  return name;
}

struct FieldShape {
  std::uint64_t components = 1;
  std::uint64_t nodes = 0;
};

// Real tags (a time) are skipped; integer tags are the time step, the
// number of components and the number of nodes (then maybe a partition).
FieldShape read_shape(io::TextCursor& cursor) {
  const std::uint64_t reals = cursor.unsigned_integer("number of real tags");
  cursor.require(reals, 2, "$NodeData real tags");
  for (std::uint64_t i = 0; i < reals; ++i) cursor.real("real tag");
  const std::uint64_t integers = cursor.unsigned_integer("number of integer tags");
  if (integers < 3) cursor.fail("$NodeData needs 3 integer tags (step, components, nodes)");
  cursor.require(integers, 2, "$NodeData integer tags");
  FieldShape shape;
  for (std::uint64_t i = 0; i < integers; ++i) {
    const std::uint64_t value = cursor.unsigned_integer("integer tag");
    if (i == 1) shape.components = value;
    if (i == 2) shape.nodes = value;
  }
  if (shape.components == 0 || shape.components > 9)
    cursor.fail("$NodeData with " + std::to_string(shape.components) + " components per node");
  return shape;
}

template <class Source, class ReadTag>
void read_records(Source& source, const FieldShape& shape, ReadTag&& read_tag, MshNodeField& field) {
  source.require(shape.nodes, 1 + shape.components, "$NodeData");
  const bool keep = shape.components == 1;
  if (keep) field.tags.reserve(shape.nodes), field.values.reserve(shape.nodes);
  for (std::uint64_t i = 0; i < shape.nodes; ++i) {
    const std::uint64_t tag = read_tag(source);
    for (std::uint64_t c = 0; c < shape.components; ++c) {
      const double value = source.real("node value");
      if (keep) field.tags.push_back(tag), field.values.push_back(value);
    }
  }
}

}  // namespace

void read_msh_node_data(io::TextCursor& cursor, const MshEncoding& encoding, MshContent& content) {
  MshNodeField field;
  field.name = read_name(cursor);
  const FieldShape shape = read_shape(cursor);
  if (encoding.binary) {
    cursor.skip_line();
    BinarySource source(cursor, encoding);
    // A node tag is an int here in both versions (gmsh and meshio read
    // and write it so in 4.1 too, where $Nodes has size_t tags).
    read_records(
        source, shape,
        [&](BinarySource& s) -> std::uint64_t {
          const std::int32_t tag = s.int32("node tag");
          if (tag < 0) cursor.fail("negative node tag " + std::to_string(tag));
          return std::uint64_t(tag);
        },
        field);
  } else {
    AsciiSource source(cursor);
    read_records(
        source, shape, [](AsciiSource& s) { return s.size("node tag"); }, field);
  }
  if (shape.components == 1) content.node_fields.push_back(std::move(field));
}

}  // namespace mr::plugins::tet
