// A set of (key, index) entries, each index 0..size-1 at most once, whose keys change in place,
// walked in ascending (key, index) order without being changed. The hubs' lazy arc streams
// (hub_arcs.hpp): a key changes for every node a search settles, so an update must neither
// allocate nor rebalance. The entries form a binary min-heap in one array (an update is a sift),
// and a walk visits the heap best first: a small frontier of heap positions, each position's
// children entering it when it is passed, so the k-th entry walked costs O(log k).
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace fnet {

class KeyedIndex {
 public:
  using Entry = std::pair<double, std::uint32_t>;  // (key, index), ordered as a pair

  explicit KeyedIndex(std::uint32_t size = 0) : position_(size, kAbsent) {}

  bool contains(std::uint32_t index) const { return position_[index] != kAbsent; }
  std::size_t size() const { return heap_.size(); }

  // Files index under key, or moves it there (nothing to do when it is filed there already).
  void set(std::uint32_t index, double key) {
    if (!contains(index)) {
      position_[index] = static_cast<std::uint32_t>(heap_.size());
      heap_.push_back({key, index});
      sift_up(position_[index]);
      return;
    }
    const std::uint32_t k = position_[index];
    if (heap_[k].first == key) return;
    const Entry old = heap_[k];
    heap_[k].first = key;
    if (heap_[k] < old) {
      sift_up(k);
    } else {
      sift_down(k);
    }
  }

  void erase(std::uint32_t index) {  // nothing when index is not filed
    if (!contains(index)) return;
    const std::uint32_t k = position_[index];
    position_[index] = kAbsent;
    const Entry last = heap_.back();
    heap_.pop_back();
    if (k == heap_.size()) return;
    const Entry old = heap_[k];
    heap_[k] = last;
    position_[last.second] = k;
    if (last < old) {
      sift_up(k);
    } else {
      sift_down(k);
    }
  }

  // The walk: every entry once, in ascending order, while the entries stay as they are.
  void walk_start() {
    frontier_.clear();
    if (!heap_.empty()) frontier_.push_back(0);
  }
  bool walk_done() const { return frontier_.empty(); }
  const Entry& walk_head() const { return heap_[frontier_.front()]; }  // not when done
  void walk_next() {
    const auto later = [this](std::uint32_t p, std::uint32_t r) { return heap_[r] < heap_[p]; };
    std::pop_heap(frontier_.begin(), frontier_.end(), later);
    const std::uint32_t k = frontier_.back();
    frontier_.pop_back();
    for (const std::uint32_t child : {2 * k + 1, 2 * k + 2}) {
      if (child >= heap_.size()) break;
      frontier_.push_back(child);
      std::push_heap(frontier_.begin(), frontier_.end(), later);
    }
  }

 private:
  static constexpr std::uint32_t kAbsent = std::numeric_limits<std::uint32_t>::max();

  void place(std::uint32_t k, const Entry& e) {
    heap_[k] = e;
    position_[e.second] = k;
  }
  void sift_up(std::uint32_t k) {
    const Entry e = heap_[k];
    while (k > 0) {
      const std::uint32_t parent = (k - 1) / 2;
      if (!(e < heap_[parent])) break;
      place(k, heap_[parent]);
      k = parent;
    }
    place(k, e);
  }
  void sift_down(std::uint32_t k) {
    const Entry e = heap_[k];
    const auto n = static_cast<std::uint32_t>(heap_.size());
    for (;;) {
      std::uint32_t child = 2 * k + 1;
      if (child >= n) break;
      if (child + 1 < n && heap_[child + 1] < heap_[child]) ++child;
      if (!(heap_[child] < e)) break;
      place(k, heap_[child]);
      k = child;
    }
    place(k, e);
  }

  std::vector<Entry> heap_;
  std::vector<std::uint32_t> position_;  // of each index in heap_, kAbsent when not filed
  std::vector<std::uint32_t> frontier_;  // the walk's heap positions, a min-heap by their entries
};

}  // namespace fnet
