// MSH 4.1 $Entities, $Nodes and $Elements, ASCII and binary
// (https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format).

#include "msh_sections.h"

#include <array>
#include <string>

namespace mr::plugins::tet {
namespace {

template <class Source>
void skip_values(Source& source, std::uint64_t count, const char* what) {
  source.require(count, 1, what);
  for (std::uint64_t i = 0; i < count; ++i) source.int32(what);
}

// One entity line: tag, point or bounding box, physical tags, and for curves,
// surfaces and volumes the tags of their bounding entities.
template <class Source>
void read_entity(Source& source, int dim, EntityLabels& labels) {
  const std::int32_t tag = source.int32("entity tag");
  for (int i = 0; i < (dim == 0 ? 3 : 6); ++i) source.real("entity coordinates");
  const std::uint64_t physical_count = source.size("number of physical tags");
  source.require(physical_count, 1, "physical tags");
  for (std::uint64_t i = 0; i < physical_count; ++i) {
    const std::int32_t physical = source.int32("physical tag");
    if (i == 0) labels[entity_key(dim, tag)] = physical;
  }
  if (dim > 0) skip_values(source, source.size("number of bounding entities"), "bounding entity tags");
}

template <class Source>
void read_entities(Source& source, EntityLabels& labels) {
  std::array<std::uint64_t, 4> counts{};
  for (auto& count : counts) count = source.size("number of entities");
  for (int dim = 0; dim < 4; ++dim) {
    source.require(counts[dim], dim == 0 ? 5 : 9, "$Entities");
    for (std::uint64_t i = 0; i < counts[dim]; ++i) read_entity(source, dim, labels);
  }
}

template <class Source>
void read_node_block(Source& source, MshContent& content) {
  const std::int32_t dim = source.int32("entity dimension");
  source.int32("entity tag");
  const std::int32_t parametric = source.int32("parametric flag");
  const std::uint64_t count = source.size("number of nodes in block");
  if (dim < 0 || dim > 3) source.cursor().fail("node block of dimension " + std::to_string(dim));
  const int extra = parametric ? dim : 0;
  source.require(count, 4 + extra, "node block");
  for (std::uint64_t i = 0; i < count; ++i) content.node_tags.push_back(source.size("node tag"));
  for (std::uint64_t i = 0; i < count; ++i) {
    const double x = source.real("x"), y = source.real("y"), z = source.real("z");
    content.positions.emplace_back(x, y, z);
    for (int k = 0; k < extra; ++k) source.real("parametric coordinate");
  }
}

template <class Source>
void read_nodes(Source& source, MshContent& content) {
  const std::uint64_t blocks = source.size("number of node blocks");
  const std::uint64_t nodes = source.size("number of nodes");
  source.size("minimum node tag");
  source.size("maximum node tag");
  source.require(blocks, 4, "$Nodes blocks");
  source.require(nodes, 4, "$Nodes");
  const std::size_t before = content.positions.size();
  content.positions.reserve(before + nodes);
  content.node_tags.reserve(before + nodes);
  for (std::uint64_t b = 0; b < blocks; ++b) read_node_block(source, content);
  if (content.positions.size() - before != nodes)
    source.cursor().fail("$Nodes declares " + std::to_string(nodes) + " nodes but its blocks hold " +
                         std::to_string(content.positions.size() - before));
}

template <class Source>
void read_element_block(Source& source, const EntityLabels& labels, MshContent& content) {
  const std::int32_t dim = source.int32("entity dimension");
  const std::int32_t entity = source.int32("entity tag");
  const std::int32_t type = source.int32("element type");
  const std::uint64_t count = source.size("number of elements in block");
  const int node_count = msh_element_node_count(type);
  if (node_count == 0) source.cursor().fail("unsupported element type " + std::to_string(type));
  source.require(count, 1 + static_cast<std::uint64_t>(node_count), "element block");
  const auto label_it = labels.find(entity_key(dim, entity));
  const std::int32_t label = label_it != labels.end() ? label_it->second : entity;
  std::array<std::uint64_t, 4> nodes{};
  for (std::uint64_t e = 0; e < count; ++e) {
    source.size("element tag");
    for (int k = 0; k < node_count; ++k) {
      const std::uint64_t node = source.size("element node tag");
      if (k < 4) nodes[k] = node;
    }
    content.add_element(type, nodes.data(), label);
  }
}

template <class Source>
void read_elements(Source& source, const EntityLabels& labels, MshContent& content) {
  const std::uint64_t blocks = source.size("number of element blocks");
  const std::uint64_t elements = source.size("number of elements");
  source.size("minimum element tag");
  source.size("maximum element tag");
  source.require(blocks, 4, "$Elements blocks");
  source.require(elements, 2, "$Elements");
  for (std::uint64_t b = 0; b < blocks; ++b) read_element_block(source, labels, content);
}

}  // namespace

void read_msh4_entities(io::TextCursor& cursor, const MshEncoding& encoding, EntityLabels& labels) {
  if (encoding.binary) {
    BinarySource source(cursor, encoding);
    read_entities(source, labels);
  } else {
    AsciiSource source(cursor);
    read_entities(source, labels);
  }
}

void read_msh4_nodes(io::TextCursor& cursor, const MshEncoding& encoding, MshContent& content) {
  if (encoding.binary) {
    BinarySource source(cursor, encoding);
    read_nodes(source, content);
  } else {
    AsciiSource source(cursor);
    read_nodes(source, content);
  }
}

void read_msh4_elements(io::TextCursor& cursor, const MshEncoding& encoding, const EntityLabels& labels,
                        MshContent& content) {
  if (encoding.binary) {
    BinarySource source(cursor, encoding);
    read_elements(source, labels, content);
  } else {
    AsciiSource source(cursor);
    read_elements(source, labels, content);
  }
}

}  // namespace mr::plugins::tet
