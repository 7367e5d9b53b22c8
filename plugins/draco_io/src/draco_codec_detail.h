#pragma once
// Plugin-internal entry points of the Draco codec. The public encode_draco /
// decode_draco (used by glTF) leave face regions out; the .drc format carries
// them as a GENERIC attribute tagged with attribute metadata name=face_region.

#include <mr/plugins/draco_codec.h>

namespace mr::plugins::detail {

/// Metadata entry that marks the face-region attribute in a .drc file.
inline constexpr const char* kRegionMetadataKey = "name";
inline constexpr const char* kRegionMetadataValue = "face_region";

DracoEncoded encode_draco_mesh(const TriangleSoup& soup, const io::DracoOptions& options, bool with_regions);

TriangleSoup decode_draco_mesh(std::string_view bytes, const std::string& source,
                               const DracoAttributeIds& ids, bool with_regions);

}  // namespace mr::plugins::detail
