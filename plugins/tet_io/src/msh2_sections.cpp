// MSH 2.2 $Nodes and $Elements, ASCII and binary. In binary files the counts
// stay in ASCII on their own line and the records follow as raw bytes.

#include "msh_sections.h"

#include <array>
#include <string>

namespace mr::plugins::tet {
namespace {

// Label of an MSH 2 element: its physical tag, or its elementary tag when the
// physical tag is absent or 0 (gmsh's "no physical group").
std::int32_t label_from_tags(std::int32_t physical, std::int32_t elementary, std::uint64_t tag_count) {
  if (tag_count >= 1 && physical != 0) return physical;
  return tag_count >= 2 ? elementary : 0;
}

void read_ascii_nodes(io::TextCursor& cursor, MshContent& content, std::uint64_t count) {
  cursor.require(count, 8, "$Nodes");
  content.positions.reserve(content.positions.size() + count);
  content.node_tags.reserve(content.node_tags.size() + count);
  for (std::uint64_t i = 0; i < count; ++i) {
    content.node_tags.push_back(cursor.unsigned_integer("node number"));
    const double x = cursor.real("x"), y = cursor.real("y"), z = cursor.real("z");
    content.positions.emplace_back(x, y, z);
  }
}

void read_binary_nodes(io::TextCursor& cursor, const MshEncoding& encoding, MshContent& content,
                       std::uint64_t count) {
  BinarySource source(cursor, encoding);
  cursor.require(count, 4 + 3 * 8, "$Nodes");
  content.positions.reserve(content.positions.size() + count);
  content.node_tags.reserve(content.node_tags.size() + count);
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::int32_t tag = source.int32("node number");
    if (tag < 0) cursor.fail("negative node number " + std::to_string(tag));
    content.node_tags.push_back(static_cast<std::uint64_t>(tag));
    const double x = source.real("x"), y = source.real("y"), z = source.real("z");
    content.positions.emplace_back(x, y, z);
  }
}

void read_ascii_elements(io::TextCursor& cursor, MshContent& content, std::uint64_t count) {
  cursor.require(count, 8, "$Elements");
  std::array<std::uint64_t, 4> nodes{};
  for (std::uint64_t e = 0; e < count; ++e) {
    cursor.unsigned_integer("element number");
    const std::int32_t type = cursor.int32("element type");
    const int node_count = msh_element_node_count(type);
    if (node_count == 0) cursor.fail("unsupported element type " + std::to_string(type));
    const std::uint64_t tag_count = cursor.unsigned_integer("number of tags");
    std::int32_t physical = 0, elementary = 0;
    for (std::uint64_t t = 0; t < tag_count; ++t) {
      const std::int32_t value = cursor.int32("element tag");
      if (t == 0) physical = value;
      if (t == 1) elementary = value;
    }
    for (int k = 0; k < node_count; ++k) {
      const std::uint64_t node = cursor.unsigned_integer("element node number");
      if (k < 4) nodes[k] = node;
    }
    content.add_element(type, nodes.data(), label_from_tags(physical, elementary, tag_count));
  }
}

// Binary elements come in blocks: a header (type, count, number of tags)
// followed by `count` records of int32 values.
void read_binary_elements(io::TextCursor& cursor, const MshEncoding& encoding, MshContent& content,
                          std::uint64_t count) {
  BinarySource source(cursor, encoding);
  std::array<std::uint64_t, 4> nodes{};
  for (std::uint64_t read = 0; read < count;) {
    const std::int32_t type = source.int32("element type");
    const std::int32_t block = source.int32("elements in block");
    const std::int32_t tag_count = source.int32("number of tags");
    const int node_count = msh_element_node_count(type);
    if (node_count == 0) cursor.fail("unsupported element type " + std::to_string(type));
    if (block <= 0 || static_cast<std::uint64_t>(block) > count - read || tag_count < 0)
      cursor.fail("corrupt element block header (" + std::to_string(block) + " elements, " +
                  std::to_string(tag_count) + " tags)");
    cursor.require(static_cast<std::uint64_t>(block), 4 * (1 + std::uint64_t(tag_count) + node_count),
                   "element block");
    for (std::int32_t e = 0; e < block; ++e) {
      source.int32("element number");
      std::int32_t physical = 0, elementary = 0;
      for (std::int32_t t = 0; t < tag_count; ++t) {
        const std::int32_t value = source.int32("element tag");
        if (t == 0) physical = value;
        if (t == 1) elementary = value;
      }
      for (int k = 0; k < node_count; ++k) {
        const std::int32_t node = source.int32("element node number");
        if (k < 4) nodes[k] = static_cast<std::uint32_t>(node);
      }
      content.add_element(type, nodes.data(),
                          label_from_tags(physical, elementary, std::uint64_t(tag_count)));
    }
    read += static_cast<std::uint64_t>(block);
  }
}

}  // namespace

void read_msh2_nodes(io::TextCursor& cursor, const MshEncoding& encoding, MshContent& content) {
  const std::uint64_t count = cursor.unsigned_integer("number of nodes");
  if (!encoding.binary) return read_ascii_nodes(cursor, content, count);
  cursor.skip_line();
  read_binary_nodes(cursor, encoding, content, count);
}

void read_msh2_elements(io::TextCursor& cursor, const MshEncoding& encoding, MshContent& content) {
  const std::uint64_t count = cursor.unsigned_integer("number of elements");
  if (!encoding.binary) return read_ascii_elements(cursor, content, count);
  cursor.skip_line();
  read_binary_elements(cursor, encoding, content, count);
}

}  // namespace mr::plugins::tet
