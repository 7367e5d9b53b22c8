#pragma once
// The holes of a surface as loops of border edges.

#include <mr/core/triangle_soup.h>

#include <vector>

namespace mr::hole_fill::detail {

/// A hole's border, in the direction a patch face must traverse it so that
/// the patch is oriented like the faces around it: the edge from
/// vertices[i] to vertices[i + 1] (cyclically) is an edge of one input
/// face, traversed by that face the other way round (by most of them, where
/// the faces around the hole disagree on orientation); opposite[i] is that
/// face's third vertex.
struct BorderLoop {
  std::vector<Index> vertices;
  std::vector<Index> opposite;
};

struct BorderLoops {
  std::vector<BorderLoop> loops;
  /// Border edges on no loop: paths ending at a vertex with an odd number
  /// of border edges (where an edge of three or more faces meets the border).
  std::size_t open_edges = 0;
};

/// Every simple loop of border edges (an edge of exactly one face;
/// degenerate faces ignored) of a soup welded by index. A walk that comes
/// back to a vertex it passed (a pinched border) gives the loop it closed
/// and goes on, so every loop visits each vertex once. Edges are walked
/// either way round and a loop runs the way most of its faces ask, so a
/// border whose faces disagree on orientation is a loop too.
/// Deterministic: walks start at the lowest unused border edge of the face
/// order and take the lowest unused edge at each vertex.
BorderLoops find_border_loops(const TriangleSoup& welded);

}  // namespace mr::hole_fill::detail
