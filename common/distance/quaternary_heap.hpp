// A min-heap of (key, id) entries with four children per node: half the depth of a binary heap,
// and a node's children share a cache line, which is what the shortest-path searches of
// diagonal_flow.cpp spend most of their time on (pushing and popping tree boxes and nodes).
// Entries are ordered by (key, id), so the order they pop in is the binary heap's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace fnet {

class QuaternaryHeap {
 public:
  using Entry = std::pair<double, std::int64_t>;

  bool empty() const { return entries_.empty(); }
  void clear() { entries_.clear(); }

  void push(Entry e) {
    std::size_t k = entries_.size();
    entries_.push_back(e);
    while (k > 0) {
      const std::size_t parent = (k - 1) / 4;
      if (!(e < entries_[parent])) break;
      entries_[k] = entries_[parent];
      k = parent;
    }
    entries_[k] = e;
  }

  // The least entry, removed. Not on an empty heap.
  Entry pop() {
    const Entry top = entries_.front();
    const Entry last = entries_.back();
    entries_.pop_back();
    const std::size_t n = entries_.size();
    if (n == 0) return top;
    std::size_t k = 0;
    for (;;) {
      const std::size_t first = 4 * k + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t end = first + 4 < n ? first + 4 : n;
      for (std::size_t c = first + 1; c < end; ++c)
        if (entries_[c] < entries_[best]) best = c;
      if (!(entries_[best] < last)) break;
      entries_[k] = entries_[best];
      k = best;
    }
    entries_[k] = last;
    return top;
  }

 private:
  std::vector<Entry> entries_;
};

}  // namespace fnet
