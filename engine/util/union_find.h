// Disjoint sets over 0..n-1 (path halving; the smaller index becomes the root, so a set's root
// is its smallest member). UnionFind is not thread-safe; ConcurrentUnionFind may be used from
// many threads at once (lock-free: a root is linked under a smaller root by compare-and-swap),
// and ends with the same sets and roots whatever the order of the unions.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace strata {

struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

struct ConcurrentUnionFind {
  std::vector<std::atomic<uint32_t>> parent;
  explicit ConcurrentUnionFind(size_t n) : parent(n) {
    for (size_t i = 0; i < n; ++i) parent[i].store(uint32_t(i), std::memory_order_relaxed);
  }
  // Parents only ever point to smaller indices of the same set, so halving a path (pointing a
  // node at its grandparent) by compare-and-swap never loses a union.
  uint32_t find(uint32_t x) {
    for (;;) {
      uint32_t p = parent[x].load(std::memory_order_acquire);
      if (p == x) return x;
      const uint32_t grand = parent[p].load(std::memory_order_acquire);
      if (grand != p) parent[x].compare_exchange_weak(p, grand, std::memory_order_acq_rel);
      x = grand;
    }
  }
  void unite(uint32_t a, uint32_t b) {
    for (;;) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);  // link the larger root under the smaller
      uint32_t expected = a;
      if (parent[a].compare_exchange_strong(expected, b, std::memory_order_acq_rel)) return;
    }
  }
};

// Dense numbers for the sets of a partition given each element's root, where a root is its
// set's smallest member (as both finds above leave it): element i gets the rank of its root
// among all roots in index order, so sets are numbered 0, 1, ... in order of their first member.
// *sets receives the count. Parallel over fixed chunks (parallel_for.h); the same on any
// thread count.
std::vector<uint32_t> numberSetsByRoot(const std::vector<uint32_t>& rootOf, uint32_t* sets);

}  // namespace strata
