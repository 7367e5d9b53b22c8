#pragma once
// Where each face of a repaired surface came from: an input triangle kept
// as it was, a face on an input triangle that was cut or moved, or a face
// filled where the input had no surface (meshrepair --provenance, --stats).

#include <mr/core/coordinate_grid.h>
#include <mr/core/triangle_soup.h>

#include <cstdint>
#include <vector>

namespace mr::check {

enum class FaceSource : std::uint8_t {
  kept,    ///< the corners of an input triangle, as the output grid holds them
  recut,   ///< within epsilon of an input triangle (the nearest to its centroid)
  filled,  ///< farther than epsilon from every input triangle
};

struct FaceProvenance {
  /// Per output face: the input triangle it is or lies on; -1 when filled.
  std::vector<std::int64_t> input_face;
  std::vector<FaceSource> source;
};

/// Provenance of every face of `output`. A face is kept when its three
/// positions are, as a set, the corners of an input triangle rounded onto
/// `grid` (the grid the output was written on).
FaceProvenance face_provenance(const TriangleSoup& output, const TriangleSoup& input,
                               const CoordinateGrid& grid, double epsilon);

struct ProvenanceSummary {
  std::size_t kept_faces = 0, recut_faces = 0, filled_faces = 0;
  double kept_area = 0.0, recut_area = 0.0, filled_area = 0.0;
  /// Input triangles that are among the output's faces.
  std::size_t input_triangles_kept = 0;

  double kept_area_share() const;
};

ProvenanceSummary summarize_provenance(const FaceProvenance& provenance, const TriangleSoup& output);

}  // namespace mr::check
