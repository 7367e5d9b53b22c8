#pragma once
// Parsers of the MSH sections that carry the mesh. Each is called with the
// cursor just after the section's name line and stops before its $End line.

#include "msh_content.h"
#include "msh_source.h"

#include <unordered_map>

namespace mr::plugins::tet {

/// Label of each entity that has a physical tag, keyed by entity_key(dim, tag).
using EntityLabels = std::unordered_map<std::uint64_t, std::int32_t>;

inline std::uint64_t entity_key(std::int32_t dim, std::int32_t tag) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(dim)) << 32) |
         static_cast<std::uint32_t>(tag);
}

void read_msh4_entities(io::TextCursor& cursor, const MshEncoding& encoding, EntityLabels& labels);
void read_msh4_nodes(io::TextCursor& cursor, const MshEncoding& encoding, MshContent& content);
void read_msh4_elements(io::TextCursor& cursor, const MshEncoding& encoding, const EntityLabels& labels,
                        MshContent& content);

void read_msh2_nodes(io::TextCursor& cursor, const MshEncoding& encoding, MshContent& content);
void read_msh2_elements(io::TextCursor& cursor, const MshEncoding& encoding, MshContent& content);

/// $NodeData (the same in both versions); keeps one-component fields.
void read_msh_node_data(io::TextCursor& cursor, const MshEncoding& encoding, MshContent& content);

}  // namespace mr::plugins::tet
