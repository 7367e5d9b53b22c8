#pragma once
// Disjoint sets over 0..n-1 with path halving: connected components of
// faces or vertices. Roots depend only on the order of unite() calls, so
// results are deterministic.

#include <cstddef>
#include <vector>

namespace mr {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) {
    parent_.reserve(n);
    for (std::size_t i = 0; i < n; ++i) parent_.push_back(i);
  }
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace mr
