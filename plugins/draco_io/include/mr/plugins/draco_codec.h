#pragma once
// Draco encoding and decoding of a triangle soup, shared by the .drc format
// and by glTF's KHR_draco_mesh_compression.

#include <mr/core/triangle_soup.h>
#include <mr/io/options.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace mr::plugins {

/// Draco attribute unique ids of each soup attribute; -1 = absent (on decode:
/// find the attribute by its semantic type instead).
struct DracoAttributeIds {
  int position = -1;
  int normal = -1;
  int uv = -1;
  int color = -1;
};

struct DracoEncoded {
  std::vector<char> bytes;
  DracoAttributeIds ids;
  /// What a decoder gets back: its point (vertex) count, the glTF accessor
  /// count (it can differ from the soup's: the edgebreaker drops isolated
  /// vertices and splits non-manifold ones), and the face count.
  std::size_t num_points = 0;
  std::size_t num_faces = 0;
};

/// Throws mr::RunError if Draco cannot encode the soup.
DracoEncoded encode_draco(const TriangleSoup& soup, const io::DracoOptions& options);

/// Throws mr::InputError naming `source` on anything that is not a valid Draco triangle mesh.
TriangleSoup decode_draco(std::string_view bytes, const std::string& source,
                          const DracoAttributeIds& ids = {});

}  // namespace mr::plugins
