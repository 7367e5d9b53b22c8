#include "face_grid.h"

#include <algorithm>
#include <cmath>

namespace mr::simplify {
namespace {

constexpr std::int64_t kCellRange = std::int64_t(1) << 21;

}  // namespace

FaceGrid::FaceGrid(const Vec3d& origin, double cell_size) : origin_(origin), cell_size_(cell_size) {}

std::array<std::int64_t, 3> FaceGrid::cell_of(const Vec3d& p) const {
  std::array<std::int64_t, 3> c{};
  for (int k = 0; k < 3; ++k) {
    const double x = std::floor((p[k] - origin_[k]) / cell_size_);
    c[k] = static_cast<std::int64_t>(std::clamp(x, 0.0, double(kCellRange - 1)));
  }
  return c;
}

std::uint64_t FaceGrid::key(std::int64_t x, std::int64_t y, std::int64_t z) {
  return (std::uint64_t(x) << 42) | (std::uint64_t(y) << 21) | std::uint64_t(z);
}

void FaceGrid::insert(std::uint32_t face, const Vec3d& lo, const Vec3d& hi) {
  if (face >= boxes_.size()) boxes_.resize(std::size_t(face) + 1);
  Box& box = boxes_[face];
  const auto a = cell_of(lo);
  const auto b = cell_of(hi);
  const std::int64_t cells = (b[0] - a[0] + 1) * (b[1] - a[1] + 1) * (b[2] - a[2] + 1);
  const auto entries_of = [](std::int64_t n) { return n > kMaxCellsPerFace ? 0 : n; };
  live_entries_ += entries_of(cells) - entries_of(box.cells);
  box = {lo, hi, cells};
  add_entries(face, box);
  // Rebuild once stale entries are the majority: each entry is then
  // inserted a bounded number of times on average.
  if (entries_ > 2 * live_entries_ + 4096) rebuild();
}

void FaceGrid::add_entries(std::uint32_t face, const Box& box) {
  if (box.cells > kMaxCellsPerFace) {
    if (face >= in_oversize_.size()) in_oversize_.resize(face + 1, 0);
    if (!in_oversize_[face]) oversize_.push_back(face);
    in_oversize_[face] = 1;
    return;
  }
  const auto a = cell_of(box.lo);
  const auto b = cell_of(box.hi);
  for (std::int64_t x = a[0]; x <= b[0]; ++x)
    for (std::int64_t y = a[1]; y <= b[1]; ++y)
      for (std::int64_t z = a[2]; z <= b[2]; ++z) cells_[key(x, y, z)].push_back(face);
  entries_ += box.cells;
}

void FaceGrid::rebuild() {
  cells_.clear();
  oversize_.clear();
  in_oversize_.assign(in_oversize_.size(), 0);
  entries_ = 0;
  for (std::uint32_t face = 0; face < boxes_.size(); ++face) {
    if (boxes_[face].cells > 0) add_entries(face, boxes_[face]);
  }
}

// For query boxes larger than the occupied part of the grid.
void FaceGrid::collect_from_all_cells(const std::array<std::int64_t, 3>& a,
                                      const std::array<std::int64_t, 3>& b,
                                      std::vector<std::uint32_t>& out) const {
  const std::uint64_t mask = kCellRange - 1;
  for (const auto& [cell, faces] : cells_) {
    const std::array<std::int64_t, 3> c{std::int64_t(cell >> 42), std::int64_t((cell >> 21) & mask),
                                        std::int64_t(cell & mask)};
    bool overlaps = true;
    for (int k = 0; k < 3; ++k) overlaps = overlaps && c[k] >= a[k] && c[k] <= b[k];
    if (overlaps) out.insert(out.end(), faces.begin(), faces.end());
  }
}

void FaceGrid::query(const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const {
  out.assign(oversize_.begin(), oversize_.end());
  const auto a = cell_of(lo);
  const auto b = cell_of(hi);
  const double box_cells = double(b[0] - a[0] + 1) * double(b[1] - a[1] + 1) * double(b[2] - a[2] + 1);
  if (box_cells > double(cells_.size())) {
    collect_from_all_cells(a, b, out);
  } else {
    for (std::int64_t x = a[0]; x <= b[0]; ++x)
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
        for (std::int64_t z = a[2]; z <= b[2]; ++z) {
          const auto it = cells_.find(key(x, y, z));
          if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
        }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace mr::simplify
