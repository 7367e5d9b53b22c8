#pragma once
// The outer hull of a soup: the surface, offset outward by about a voxel,
// of what a voxel grid cannot reach from outside without passing near a
// triangle (less the enclosed pockets the winding number calls outside).
// It is closed whatever the soup is (crossing, crumpled, unoriented,
// duplicated), which makes it the fallback where exact insertion of the
// soup would cost too much.

#include <mr/core/triangle_soup.h>

#include <cstddef>

namespace mr::volume {

struct OuterHullOptions {
  /// Edge of a voxel, absolute (> 0).
  double voxel_size = 0.0;
  /// Voxels whose centre is closer than this to a triangle are walls, in
  /// voxels. At least sqrt(3)/2, so that the walls around a triangle leave
  /// no gap a path between voxel centres could pass.
  double wall_radius = 1.0;
  /// How far the surface moves back toward the soup once the walls have
  /// closed the solid, in voxels (a morphological closing), at most
  /// wall_radius - 1/2: what the walls made thinner than a voxel keeps a
  /// voxel's thickness.
  double closing = 0.5;
  /// 0: one quad per crossed voxel edge, up to 1: as few as OpenVDB can.
  double adaptivity = 0.0;
};

/// The surface of the voxels not reachable from outside the soup's box
/// through voxels whose centres lie farther than wall_radius from every
/// triangle, offset to that distance (OpenVDB's volumeToMesh of the level
/// set), as outward-oriented triangles. A pocket the walls enclose is
/// outside too if most of a few voxels spread over it have |winding
/// number| <= 1/2 (a hollow solid's cavity). Every point of the hull lies
/// within about (wall_radius + 1) voxels of the soup; holes wider than
/// about two wall radii let the outside in.
/// Throws RunError if the grid would have more than `max_voxels` voxels.
TriangleSoup outer_hull(const TriangleSoup& soup, const OuterHullOptions& options,
                        std::size_t max_voxels = std::size_t{1} << 28);

}  // namespace mr::volume
