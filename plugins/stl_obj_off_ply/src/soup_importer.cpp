#include "soup_importer.h"

#include <algorithm>
#include <cstring>

namespace mr::plugins::stl_obj_off_ply {

void append_fan(std::vector<Triangle>& triangles, std::span<const Index> polygon) {
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
    triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
}

std::size_t append_strip(std::vector<Triangle>& triangles, std::span<const Index> strip) {
  std::size_t added = 0;
  for (std::size_t i = 0; i + 2 < strip.size(); ++i) {
    const Index a = strip[i], b = strip[i + 1], c = strip[i + 2];
    if (a == b || b == c || a == c) continue;
    triangles.push_back(i % 2 == 0 ? Triangle{a, b, c} : Triangle{b, a, c});
    ++added;
  }
  return added;
}

std::int32_t RegionTable::id_of(std::string_view name) {
  auto [it, inserted] = ids_.try_emplace(std::string(name), static_cast<std::int32_t>(names_.size()));
  if (inserted) names_.emplace_back(name);
  return it->second;
}

namespace {

// The exact bits of a corner's three coordinates (float or double).
template <class Bits>
struct PositionKey {
  Bits x, y, z;
  bool operator==(const PositionKey&) const = default;
};

template <class Bits>
std::uint64_t hash_of(const PositionKey<Bits>& k) {
  std::uint64_t h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
  h ^= (static_cast<std::uint64_t>(k.y) + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
  h ^= (static_cast<std::uint64_t>(k.z) + 0x165667B19E3779F9ull) * 0x85EBCA77C2B2AE63ull;
  return h ^ (h >> 29);
}

// Open addressing with linear probing. A slot holds the key beside its vertex
// id + 1 (0 = empty), so a lookup costs one cache miss, and lookups are
// prefetched a few corners ahead: the table is far larger than the caches.
template <class Bits>
class WeldTable {
 public:
  explicit WeldTable(std::size_t corners) {
    std::size_t size = 1024;
    while (size < corners + corners / 3) size *= 2;  // load factor <= 3/4 even if all corners differ
    slots_.resize(size);
    mask_ = size - 1;
  }

  std::size_t slot_of(const PositionKey<Bits>& key) const { return hash_of(key) & mask_; }
  void prefetch(std::size_t slot) const { __builtin_prefetch(&slots_[slot]); }

  /// The id of `key`, or `next_id` after storing it with that id.
  Index find_or_add(const PositionKey<Bits>& key, std::size_t slot, Index next_id) {
    for (;; slot = (slot + 1) & mask_) {
      Slot& s = slots_[slot];
      if (s.id_plus_one == 0) {
        s = {key, next_id + 1};
        return next_id;
      }
      if (s.key == key) return s.id_plus_one - 1;
    }
  }

 private:
  struct Slot {
    PositionKey<Bits> key{};
    Index id_plus_one = 0;
  };
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
};

template <class Bits, class Scalar>
PositionKey<Bits> key_of(const Scalar* xyz) {
  PositionKey<Bits> key;
  std::memcpy(&key.x, xyz, sizeof(Bits));
  std::memcpy(&key.y, xyz + 1, sizeof(Bits));
  std::memcpy(&key.z, xyz + 2, sizeof(Bits));
  return key;
}

// `corner(c, xyz)` writes the coordinates of corner c into xyz[3].
template <class Scalar, class Bits, class CornerFn>
TriangleSoup weld(std::size_t triangle_count, CornerFn corner) {
  static_assert(sizeof(Scalar) == sizeof(Bits));
  constexpr std::size_t kAhead = 16;
  const std::size_t corners = 3 * triangle_count;
  TriangleSoup soup;
  soup.triangles.resize(triangle_count);
  soup.positions.reserve(corners / 4 + 16);
  WeldTable<Bits> table(corners);
  std::vector<PositionKey<Bits>> keys(kAhead);
  std::vector<std::size_t> slots(kAhead);
  Scalar xyz[3];
  auto load = [&](std::size_t c) {
    corner(c, xyz);
    keys[c % kAhead] = key_of<Bits>(xyz);
    slots[c % kAhead] = table.slot_of(keys[c % kAhead]);
    table.prefetch(slots[c % kAhead]);
  };
  for (std::size_t c = 0; c < std::min(kAhead, corners); ++c) load(c);
  for (std::size_t c = 0; c < corners; ++c) {
    const PositionKey<Bits> key = keys[c % kAhead];
    const auto next = static_cast<Index>(soup.positions.size());
    const Index id = table.find_or_add(key, slots[c % kAhead], next);
    if (id == next) {
      Scalar p[3];
      std::memcpy(p, &key, sizeof(p));
      soup.positions.emplace_back(p[0], p[1], p[2]);
    }
    soup.triangles[c / 3][c % 3] = id;
    if (c + kAhead < corners) load(c + kAhead);
  }
  soup.positions.shrink_to_fit();
  return soup;
}

}  // namespace

TriangleSoup weld_triangle_corners(const std::vector<Vec3d>& corners) {
  return weld<double, std::uint64_t>(corners.size() / 3, [&](std::size_t c, double* xyz) {
    for (int k = 0; k < 3; ++k) xyz[k] = corners[c][k];
  });
}

TriangleSoup weld_float_corners(const char* records, std::size_t count, std::size_t record_size,
                                std::size_t offset) {
  return weld<float, std::uint32_t>(count, [&](std::size_t c, float* xyz) {
    std::memcpy(xyz, records + (c / 3) * record_size + offset + (c % 3) * 3 * sizeof(float),
                3 * sizeof(float));
  });
}

}  // namespace mr::plugins::stl_obj_off_ply
