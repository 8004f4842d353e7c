// A min-heap of (key, id) entries with four children per node: half the depth of a binary heap,
// and a node's children share a cache line, which is what the shortest-path searches of
// diagonal_flow.cpp spend most of their time on (pushing and popping tree boxes and nodes).
// Entries are ordered by (key, id), so the order they pop in is the binary heap's.
// Ids in [0, tracked) are filed at most once: pushing one already filed with a smaller key moves
// it up (decrease-key) instead of leaving a stale copy behind. A W2 search after the line start
// relaxes each node it settles about six times; the stale copies were two thirds of its pops.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace fnet {

class QuaternaryHeap {
 public:
  using Entry = std::pair<double, std::int64_t>;

  explicit QuaternaryHeap(std::size_t tracked = 0) : position_(tracked, kAbsent) {}

  bool empty() const { return entries_.empty(); }
  void clear() {
    for (const Entry& e : entries_)
      if (is_tracked(e.second)) position_[static_cast<std::size_t>(e.second)] = kAbsent;
    entries_.clear();
  }

  // Files e; a tracked id already filed takes e's key if that is smaller (else nothing changes).
  void push(Entry e) {
    std::size_t k = entries_.size();
    if (is_tracked(e.second)) {
      const std::size_t at = position_[static_cast<std::size_t>(e.second)];
      if (at != kAbsent) {
        if (!(e < entries_[at])) return;
        k = at;
      } else {
        entries_.emplace_back();
      }
    } else {
      entries_.emplace_back();
    }
    while (k > 0) {
      const std::size_t parent = (k - 1) / 4;
      if (!(e < entries_[parent])) break;
      place(k, entries_[parent]);
      k = parent;
    }
    place(k, e);
  }

  // The least entry, removed. Not on an empty heap.
  Entry pop() {
    const Entry top = entries_.front();
    if (is_tracked(top.second)) position_[static_cast<std::size_t>(top.second)] = kAbsent;
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
      place(k, entries_[best]);
      k = best;
    }
    place(k, last);
    return top;
  }

 private:
  static constexpr std::size_t kAbsent = std::numeric_limits<std::size_t>::max();
  bool is_tracked(std::int64_t id) const { return id >= 0 && static_cast<std::size_t>(id) < position_.size(); }
  void place(std::size_t k, const Entry& e) {
    entries_[k] = e;
    if (is_tracked(e.second)) position_[static_cast<std::size_t>(e.second)] = k;
  }

  std::vector<Entry> entries_;
  std::vector<std::size_t> position_;  // of each tracked id in entries_, kAbsent when not filed
};

}  // namespace fnet
