#pragma once
// Carrying the input's attributes onto a repaired surface (meshrepair):
// normals, texture coordinates, vertex colours and face regions (glTF
// materials, OBJ groups) follow each output face from the input triangle
// it came from, so a repaired asset keeps its look.

#include <mr/core/coordinate_grid.h>
#include <mr/core/triangle_soup.h>

#include <cstdint>
#include <span>

namespace mr::repair {

/// `surface` with the attributes of `input`. `source[f]` is the input
/// triangle face f is or lies on, or -1 for a face filled where the input
/// had none. Each corner takes the input's per-vertex attributes exactly
/// where it is a corner of its face's source (as `grid`, the grid `surface`
/// was rounded onto, holds it); elsewhere interpolated (barycentric) at its
/// closest point on the nearest input triangle, of several as near (an
/// edge) the one facing most like its face, so that each side of a crease
/// or a UV seam reads its own values. Corners at one position whose
/// attributes differ become separate vertices (seams stay seams);
/// positions and faces are unchanged otherwise. Faces take their source's
/// region (with the input's materials and their images); filled faces a
/// region of their own named "filled" (so a viewer shows them apart), the
/// others region 0 named "input" when the input had none. Throws
/// mr::UsageError when `source` does not match `surface` or names no input
/// triangle.
TriangleSoup with_input_attributes(const TriangleSoup& surface, const TriangleSoup& input,
                                   std::span<const std::int64_t> source, const CoordinateGrid& grid);

}  // namespace mr::repair
