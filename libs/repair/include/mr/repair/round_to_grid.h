#pragma once
// The last stage of a repair: move every vertex onto the grid the output
// format stores (float32 for STL and GLB, Draco's quantization grid), so
// that the written file, not only the doubles it came from, is watertight.
// Rounding each coordinate on its own can make faces cross where two sheets
// nearly touch, collapse a sliver, or put two vertices on one grid point
// (which a reader welds into a non-manifold vertex). Here each vertex moves
// to the nearest grid point where none of that happens, decided exactly on
// the rounded coordinates; where the nearest is refused, the grid points
// around it are tried, nearest first, on widening lattices; where none
// works (sheets closer than a grid step all around it), the vertex is
// collapsed onto a placed neighbour, if that keeps the surface valid.

#include <mr/core/coordinate_grid.h>
#include <mr/core/triangle_soup.h>

#include <cstddef>
#include <functional>
#include <optional>

namespace mr::repair {

struct GridRoundingOptions {
  /// How far the search goes when the nearest grid point is refused: grid
  /// points up to this many strides from it along each axis, with strides
  /// of 1, 4, 16, ... steps up to max_stride.
  int max_steps = 8;
  int max_stride = 64;
  /// Sweeps over the vertices not yet placed (a refused vertex may fit once
  /// its neighbours have moved).
  int max_passes = 8;
  /// Positions tried over the whole run before giving up (0: no limit).
  /// round_to_grid_or_finer sets it on every grid when there is more than
  /// one: where sheets lie closer than a grid step, searching far on a grid
  /// costs more than rounding onto a finer one (or giving up).
  std::size_t max_tries = 0;
};

struct GridRoundingStats {
  std::size_t vertices = 0;
  std::size_t moved = 0;      ///< vertices that were not on the grid
  std::size_t sent_back = 0;  ///< moved vertices the whole-surface check sent back to be placed one at a time
  std::size_t nearest_refused = 0;  ///< vertices placed on a grid point other than the nearest
  std::size_t collapsed = 0;        ///< vertices no grid point worked for, collapsed onto a neighbour
  int passes = 0;
  std::size_t tries = 0;  ///< positions tried (each decided exactly against the faces near it)
  double max_move = 0.0;  ///< largest distance a vertex moved
};

/// Moves every vertex of `surface` onto `grid`. Precondition: the surface is
/// welded by index, no two vertices share a position, no face is degenerate
/// and no two faces meet except in the vertices and edges they share. All of
/// this still holds afterwards, exactly, on the grid coordinates: a vertex
/// goes to the nearest grid point where none of its faces becomes degenerate
/// or meets another face improperly and no other vertex sits, else to the
/// nearest such grid point of the search (GridRoundingOptions), else it is
/// collapsed onto the nearest placed neighbour for which the link condition
/// holds and no face becomes degenerate or meets another improperly (its
/// faces on that edge go; the surface is compacted, attributes follow).
/// First every vertex goes to its nearest grid point at once, and one exact
/// check of the whole surface sends back the corners of the faces that
/// broke (until none does); those are then placed in index order, one at a
/// time. The result is deterministic.
/// Throws mr::RunError naming the count of vertices that found no place, or
/// when the positions tried exceed options.max_tries.
GridRoundingStats round_to_grid(TriangleSoup& surface, const CoordinateGrid& grid,
                                const GridRoundingOptions& options = {});

/// A finer grid to round onto when `refused` left some vertex no place
/// (more Draco bits), or nothing. Asked before rounding onto `refused` (to
/// know whether to bound the search there), so it only computes: whoever
/// writes the file takes the grid from GridRounding::grid.
using FinerGrid = std::function<std::optional<CoordinateGrid>(const CoordinateGrid& refused)>;

struct GridRounding {
  CoordinateGrid grid;  ///< the grid the surface now lies on
  GridRoundingStats stats;
  int finer_grids = 0;  ///< grids refused before `grid`
};

/// round_to_grid onto `grid`, and while it throws, onto the grid `finer`
/// gives instead (the surface restored first); rethrows when `finer` (or
/// an empty `finer`) gives nothing. Unless `grid` is the only one, the
/// search on each is bounded (max_tries, unless options set it).
GridRounding round_to_grid_or_finer(TriangleSoup& surface, const CoordinateGrid& grid, const FinerGrid& finer,
                                    const GridRoundingOptions& options = {});

}  // namespace mr::repair
