#pragma once
// Sheets made solid: a surface that encloses no volume (a flat or
// doubled-up sheet, planes crossing like the pages of a book) turned into a
// closed soup that does, so that tools asked for a solid still have one.

#include <mr/core/triangle_soup.h>

namespace mr {

/// Each triangle of `soup` becomes a closed prism, the triangle swept
/// `half_thickness` to both sides along its normal, oriented outward (8
/// triangles). Every point of a prism is within `half_thickness` of its
/// triangle, so the union of the prisms stays that close to the input.
/// Zero-area triangles have no normal and are left out. Attributes are not
/// carried over.
TriangleSoup thicken_sheets(const TriangleSoup& soup, double half_thickness);

/// A solid at least 2 `radius` wide everywhere around every triangle, also
/// where thicken_sheets' prisms are thin: slivers, zero-area triangles, and
/// whole inputs far smaller than `radius`. Corners closer than `radius`/4
/// (in one cell of a grid that wide) are merged first; then each triangle
/// becomes its prism of half-thickness `radius`, each of its edges a box
/// around it, `radius` from the edge's line on four sides and past both its
/// ends (12 triangles). The solid holds every point within `radius`/2 of
/// the input, and each of its points is within 5/4 sqrt(3) `radius`. The
/// pieces overlap; their union is what they describe.
TriangleSoup fatten_sheets(const TriangleSoup& soup, double radius);

/// The cells of a grid `cell` wide (anchored at the input's box) that
/// some triangle of `soup` meets, as the outward surface of their union: a
/// square of two triangles on each cell side that no other marked cell
/// shares. The solid holds the input, is nowhere thinner than `cell`, and
/// each of its points is within sqrt(3) `cell` of the input. For inputs a
/// few cells across: the caller bounds the count.
TriangleSoup cell_solid(const TriangleSoup& soup, double cell);

}  // namespace mr
