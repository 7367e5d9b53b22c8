#include <mr/spatial/box_grid.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mr::spatial {
namespace {

constexpr std::int64_t kCellRange = std::int64_t(1) << 21;
// A part of a cell is split once it holds more entries than this, down to
// parts 2^kMaxDepth times smaller than the cell.
constexpr std::size_t kSplitAbove = 96;
constexpr int kMaxDepth = 12;

// The float at or below x (above, for `up`): a float box rounded outward
// holds the double box.
float rounded(double x, bool up) {
  constexpr double largest = std::numeric_limits<float>::max();
  if (x > largest) return up ? std::numeric_limits<float>::infinity() : std::numeric_limits<float>::max();
  if (x < -largest) return up ? -std::numeric_limits<float>::max() : -std::numeric_limits<float>::infinity();
  const auto f = static_cast<float>(x);
  if (up) return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

}  // namespace

BoxGrid::BoxGrid(const Vec3d& origin, double cell_size) : origin_(origin), cell_size_(cell_size) {}

Vec3d BoxGrid::grid_coordinates(const Vec3d& p) const {
  return Vec3d((p[0] - origin_[0]) / cell_size_, (p[1] - origin_[1]) / cell_size_,
               (p[2] - origin_[2]) / cell_size_);
}

BoxGrid::Cell BoxGrid::cell_of(const Vec3d& p) const {
  const Vec3d x = grid_coordinates(p);
  Cell c{};
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<std::int64_t>(std::clamp(std::floor(x[k]), 0.0, double(kCellRange - 1)));
  return c;
}

// Scaling by 2^depth is exact, so a point in cell c has its index at depth
// d in [c 2^d, (c + 1) 2^d); clamping to that range keeps the order of
// points, which is all the loose octree needs: a point in a box and in a
// query box has its index in both spans.
BoxGrid::Span BoxGrid::span_at(const Vec3d& lo, const Vec3d& hi, const Cell& cell, int depth) {
  const double scale = std::ldexp(1.0, depth);
  Span span;
  for (int k = 0; k < 3; ++k) {
    const double first = double(cell[k]) * scale, last = first + scale - 1.0;
    span.lo[k] = static_cast<std::int64_t>(std::clamp(std::floor(lo[k] * scale), first, last));
    span.hi[k] = static_cast<std::int64_t>(std::clamp(std::floor(hi[k] * scale), first, last));
  }
  return span;
}

std::uint64_t BoxGrid::key(std::int64_t x, std::int64_t y, std::int64_t z) {
  return (std::uint64_t(x) << 42) | (std::uint64_t(y) << 21) | std::uint64_t(z);
}

namespace {

std::int64_t entries_of(std::int64_t cells, std::int64_t max_cells) { return cells > max_cells ? 0 : cells; }

}  // namespace

std::int64_t BoxGrid::cells_spanned(const Vec3d& lo, const Vec3d& hi) const {
  const auto a = cell_of(lo);
  const auto b = cell_of(hi);
  return (b[0] - a[0] + 1) * (b[1] - a[1] + 1) * (b[2] - a[2] + 1);
}

void BoxGrid::erase(std::uint32_t face) {
  if (face >= boxes_.size()) return;
  live_entries_ -= entries_of(boxes_[face].cells, kMaxCellsPerFace);
  boxes_[face].cells = 0;
}

void BoxGrid::insert(std::uint32_t face, const Vec3d& lo, const Vec3d& hi) {
  if (face >= boxes_.size()) boxes_.resize(std::size_t(face) + 1);
  Box& box = boxes_[face];
  const std::int64_t cells = cells_spanned(lo, hi);
  live_entries_ += entries_of(cells, kMaxCellsPerFace) - entries_of(box.cells, kMaxCellsPerFace);
  box = {lo, hi, cells, cell_of(lo)};
  add_entries(face, box);
  // Rebuild once stale entries are the majority: each entry is then
  // inserted a bounded number of times on average.
  if (entries_ > 2 * live_entries_ + 4096) rebuild();
}

void BoxGrid::add_entries(std::uint32_t face, const Box& box) {
  if (box.cells > kMaxCellsPerFace) {
    if (face >= in_oversize_.size()) in_oversize_.resize(face + 1, 0);
    if (!in_oversize_[face]) oversize_.push_back(face);
    in_oversize_[face] = 1;
    return;
  }
  Entry entry;
  entry.id = face;
  for (int k = 0; k < 3; ++k) {
    entry.lo[k] = rounded(box.lo[k], false);
    entry.hi[k] = rounded(box.hi[k], true);
  }
  const Cell& a = box.first;
  const Cell b = cell_of(box.hi);
  const std::pair<Vec3d, Vec3d> at = entry_coordinates(entry);
  for (std::int64_t x = a[0]; x <= b[0]; ++x)
    for (std::int64_t y = a[1]; y <= b[1]; ++y)
      for (std::int64_t z = a[2]; z <= b[2]; ++z)
        add_to_node(cells_[key(x, y, z)], {x, y, z}, at, entry, {x, y, z}, 0);
  entries_ += box.cells;
}

namespace {

// The part of depth + 1 an entry spanning `span` at that depth belongs
// to, as a half (0 to 7) of `part` (at depth), or -1 when it stays.
using Index3 = std::array<std::int64_t, 3>;  // BoxGrid's Cell

int half_for(const Index3& lo, const Index3& hi, const Index3& part) {
  int half = 0;
  for (int k = 0; k < 3; ++k) {
    if (hi[k] - lo[k] > 2) return -1;
    const std::int64_t middle = lo[k] + (hi[k] - lo[k]) / 2;
    const std::int64_t offset = middle - 2 * part[k];
    if (offset != 0 && offset != 1) return -1;
    half |= int(offset) << k;
  }
  return half;
}

Index3 half_index(const Index3& part, int half) {
  return {2 * part[0] + (half & 1), 2 * part[1] + ((half >> 1) & 1), 2 * part[2] + ((half >> 2) & 1)};
}

}  // namespace

std::pair<Vec3d, Vec3d> BoxGrid::entry_coordinates(const Entry& entry) const {
  return {grid_coordinates(Vec3d(entry.lo[0], entry.lo[1], entry.lo[2])),
          grid_coordinates(Vec3d(entry.hi[0], entry.hi[1], entry.hi[2]))};
}

void BoxGrid::add_to_node(Node& node, const Cell& cell, const std::pair<Vec3d, Vec3d>& at, const Entry& entry,
                          Cell part, int depth) {
  Node* target = &node;
  while (target->halves) {
    const Span span = span_at(at.first, at.second, cell, depth + 1);
    const int half = half_for(span.lo, span.hi, part);
    if (half < 0) break;
    target = &(*target->halves)[half];
    part = half_index(part, half);
    ++depth;
  }
  target->entries.push_back(entry);
  if (target->entries.size() > kSplitAbove && depth < kMaxDepth && !target->halves)
    split(*target, cell, part, depth);
}

void BoxGrid::split(Node& node, const Cell& cell, const Cell& part, int depth) {
  node.halves = std::make_unique<std::array<Node, 8>>();
  std::vector<Entry> staying;
  for (const Entry& entry : node.entries) {
    const auto at = entry_coordinates(entry);
    const Span span = span_at(at.first, at.second, cell, depth + 1);
    const int half = half_for(span.lo, span.hi, part);
    if (half < 0) {
      staying.push_back(entry);
    } else {
      add_to_node((*node.halves)[half], cell, at, entry, half_index(part, half), depth + 1);
    }
  }
  node.entries = std::move(staying);
}

void BoxGrid::rebuild() {
  double extent = 0.0;
  std::size_t live = 0;
  for (const Box& box : boxes_) {
    if (box.cells == 0) continue;
    extent += (box.hi - box.lo).maxCoeff();
    ++live;
  }
  if (live != 0) cell_size_ = std::max(cell_size_, 2.0 * extent / double(live));
  cells_.clear();
  oversize_.clear();
  in_oversize_.assign(in_oversize_.size(), 0);
  entries_ = 0;
  live_entries_ = 0;
  for (std::uint32_t face = 0; face < boxes_.size(); ++face) {
    Box& box = boxes_[face];
    if (box.cells == 0) continue;
    box.cells = cells_spanned(box.lo, box.hi);
    box.first = cell_of(box.lo);
    live_entries_ += entries_of(box.cells, kMaxCellsPerFace);
    add_entries(face, box);
  }
}

bool BoxGrid::overlaps(std::uint32_t face, const Vec3d& lo, const Vec3d& hi) const {
  const Box& box = boxes_[face];
  if (box.cells == 0) return false;  // erased
  for (int k = 0; k < 3; ++k) {
    if (box.hi[k] < lo[k] || box.lo[k] > hi[k]) return false;
  }
  return true;
}

// Each face is taken from one cell only: the lowest cell that both its box
// and the query box cover (faces spanning several cells are otherwise listed
// once per cell, and sorting the repeats away took most of the query time).
// Oversized faces come from their own list. An entry's own box decides
// first; a stale one (its face moved or erased since) may pass it, and then
// the face's current box decides.
void BoxGrid::append_overlapping(const std::vector<Entry>& entries, const Cell& cell, const Cell& query_first,
                                 const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const {
  for (const Entry& entry : entries) {
    bool meets = true;
    for (int k = 0; k < 3; ++k) meets = meets && double(entry.hi[k]) >= lo[k] && double(entry.lo[k]) <= hi[k];
    if (!meets) continue;
    const Box& box = boxes_[entry.id];
    if (box.cells > kMaxCellsPerFace || !overlaps(entry.id, lo, hi)) continue;
    bool first_common_cell = true;
    for (int k = 0; k < 3; ++k)
      first_common_cell = first_common_cell && std::max(box.first[k], query_first[k]) == cell[k];
    if (first_common_cell) out.push_back(entry.id);
  }
}

void BoxGrid::append_from_cell(const Node& node, const Cell& cell, const Cell& query_first, const Vec3d& lo,
                               const Vec3d& hi, std::vector<std::uint32_t>& out) const {
  if (!node.halves) {
    append_overlapping(node.entries, cell, query_first, lo, hi, out);
    return;
  }
  visit(node, cell, query_first, lo, hi, {grid_coordinates(lo), grid_coordinates(hi)}, cell, 0, out);
}

// A half may hold an entry that meets the query only if their spans at the
// half's depth come within one index of it: the entry's span lies within
// one index of the half, and a common point has its index in both.
void BoxGrid::visit(const Node& node, const Cell& cell, const Cell& query_first, const Vec3d& lo,
                    const Vec3d& hi, const std::pair<Vec3d, Vec3d>& query_at, const Cell& part, int depth,
                    std::vector<std::uint32_t>& out) const {
  append_overlapping(node.entries, cell, query_first, lo, hi, out);
  if (!node.halves) return;
  const Span span = span_at(query_at.first, query_at.second, cell, depth + 1);
  for (int half = 0; half < 8; ++half) {
    const Node& child = (*node.halves)[half];
    if (child.entries.empty() && !child.halves) continue;
    const auto index = half_index(part, half);
    bool near = true;
    for (int k = 0; k < 3; ++k) near = near && span.lo[k] <= index[k] + 1 && span.hi[k] >= index[k] - 1;
    if (near) visit(child, cell, query_first, lo, hi, query_at, index, depth + 1, out);
  }
}

// For query boxes larger than the occupied part of the grid.
void BoxGrid::collect_from_all_cells(const Cell& a, const Cell& b, const Vec3d& lo, const Vec3d& hi,
                                     std::vector<std::uint32_t>& out) const {
  const std::uint64_t mask = kCellRange - 1;
  for (const auto& [cell, node] : cells_) {
    const Cell c{std::int64_t(cell >> 42), std::int64_t((cell >> 21) & mask), std::int64_t(cell & mask)};
    bool inside = true;
    for (int k = 0; k < 3; ++k) inside = inside && c[k] >= a[k] && c[k] <= b[k];
    if (inside) append_from_cell(node, c, a, lo, hi, out);
  }
}

// Entries are filtered by the face's current box before sorting: stale
// entries and faces whose box misses the query's never reach the sort (on
// thingi10k/88566 meshrepair's clean-up went from 419 s to 92 s).
void BoxGrid::query(const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const {
  query_unordered(lo, hi, out);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

void BoxGrid::query_unordered(const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const {
  out.clear();
  for (const std::uint32_t face : oversize_) {
    if (overlaps(face, lo, hi)) out.push_back(face);
  }
  const auto a = cell_of(lo);
  const auto b = cell_of(hi);
  const double box_cells = double(b[0] - a[0] + 1) * double(b[1] - a[1] + 1) * double(b[2] - a[2] + 1);
  if (box_cells > double(cells_.size())) {
    collect_from_all_cells(a, b, lo, hi, out);
  } else {
    for (std::int64_t x = a[0]; x <= b[0]; ++x)
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
        for (std::int64_t z = a[2]; z <= b[2]; ++z) {
          const auto it = cells_.find(key(x, y, z));
          if (it != cells_.end()) append_from_cell(it->second, {x, y, z}, a, lo, hi, out);
        }
  }
}

}  // namespace mr::spatial
