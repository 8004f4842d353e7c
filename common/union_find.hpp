// Disjoint sets over 0..n-1 with path halving; the caller decides which root survives a union.
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

namespace fnet {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::uint32_t{0}); }

  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  // Makes `survivor` (a root) the root of `absorbed` (a root).
  void attach(std::uint32_t absorbed, std::uint32_t survivor) { parent_[absorbed] = survivor; }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace fnet
