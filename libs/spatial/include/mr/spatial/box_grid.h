#pragma once
// A uniform hash grid of boxes keyed by a dense id (faces of a changing
// mesh, in the simplification and the repair): a changed box is inserted
// again and its old entries stay behind until they outnumber the current
// ones, when the grid is rebuilt from the current boxes (on a 516k-face scan
// the stale entries made queries sort long lists most of the time). Queries
// return a superset of the ids whose current box overlaps the query box, as
// long as every id was (re)inserted with its current box; callers test the
// candidates against current geometry and skip erased ids.
//
// A cell that fills up is split as a loose octree: the cell size follows
// the mean face, and a surface peeled from crossing sheets packs tens of
// thousands of faces a thousand times smaller than that mean into a few
// cells, whose lists every query there used to read whole.

#include <mr/core/types.h>

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace mr::spatial {

class BoxGrid {
 public:
  BoxGrid() = default;
  /// `origin` should lie below every box inserted: cells are counted from
  /// it, and whatever lies below it shares the first layer of cells (still
  /// found, but crowded).
  BoxGrid(const Vec3d& origin, double cell_size);

  void insert(std::uint32_t id, const Vec3d& lo, const Vec3d& hi);
  /// Forgets an id (its entries go stale).
  void erase(std::uint32_t id);
  /// The ids whose current box overlaps [lo, hi] (closed), sorted, without repeats.
  void query(const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const;
  /// The same ids in no particular order, some possibly twice (an id moved
  /// within a cell): for callers that test each and only ask whether any
  /// fails, and would spend a tenth of their time sorting.
  void query_unordered(const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const;

 private:
  // Faces spanning more cells than this go to a list every query visits.
  static constexpr std::int64_t kMaxCellsPerFace = 64;

  using Cell = std::array<std::int64_t, 3>;

  struct Box {
    Vec3d lo, hi;
    std::int64_t cells = 0;  ///< cells the box spans; 0: not in the grid
    Cell first{};            ///< the cell of lo
  };

  // A cell's entry: the id and its box as it was inserted, rounded outward
  // to floats. Queries read the cell's entries in a row and look up the
  // current box only for entries whose box meets the query's (reading every
  // entry's current box, all over memory, took a fifth of meshrepair's
  // clean-up on openscad-nonmanifold-crash).
  struct Entry {
    std::array<float, 3> lo, hi;
    std::uint32_t id = 0;
  };

  // A cell, or a part of one at depth d (2^d parts a side): the entries
  // that fit no smaller part, then its eight halves once it has held too
  // many. An entry belongs to the part of depth d whose index is the middle
  // of the indices its box spans at depth d (clamped to the cell), if they
  // are at most three: so a part holds boxes within one part of its own
  // side (a loose octree, each entry in one place in its cell).
  struct Node {
    std::vector<Entry> entries;
    std::unique_ptr<std::array<Node, 8>> halves;
  };
  // Indices of a box's ends at some depth, per axis.
  struct Span {
    std::array<std::int64_t, 3> lo, hi;
  };

  std::int64_t cells_spanned(const Vec3d& lo, const Vec3d& hi) const;
  void add_entries(std::uint32_t face, const Box& box);
  /// Where in the grid p lies, in cells (cell_of's index before its floor).
  Vec3d grid_coordinates(const Vec3d& p) const;
  std::pair<Vec3d, Vec3d> entry_coordinates(const Entry& entry) const;
  /// The indices at `depth` of grid coordinates lo and hi, within `cell`.
  static Span span_at(const Vec3d& lo, const Vec3d& hi, const Cell& cell, int depth);
  void add_to_node(Node& node, const Cell& cell, const std::pair<Vec3d, Vec3d>& at, const Entry& entry,
                   Cell part, int depth);
  void split(Node& node, const Cell& cell, const Cell& part, int depth);
  void visit(const Node& node, const Cell& cell, const Cell& query_first, const Vec3d& lo, const Vec3d& hi,
             const std::pair<Vec3d, Vec3d>& query_at, const Cell& part, int depth,
             std::vector<std::uint32_t>& out) const;
  void rebuild();
  Cell cell_of(const Vec3d& p) const;
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z);
  bool overlaps(std::uint32_t face, const Vec3d& lo, const Vec3d& hi) const;
  void append_overlapping(const std::vector<Entry>& entries, const Cell& cell, const Cell& query_first,
                          const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const;
  void append_from_cell(const Node& node, const Cell& cell, const Cell& query_first, const Vec3d& lo,
                        const Vec3d& hi, std::vector<std::uint32_t>& out) const;
  void collect_from_all_cells(const Cell& a, const Cell& b, const Vec3d& lo, const Vec3d& hi,
                              std::vector<std::uint32_t>& out) const;

  Vec3d origin_ = Vec3d::Zero();
  double cell_size_ = 1.0;
  std::unordered_map<std::uint64_t, Node> cells_;
  std::vector<std::uint32_t> oversize_;
  std::vector<std::uint8_t> in_oversize_;
  std::vector<Box> boxes_;         ///< per face, its current box
  std::int64_t entries_ = 0;       ///< in cells_, stale ones included
  std::int64_t live_entries_ = 0;  ///< of the current boxes
};

}  // namespace mr::spatial
