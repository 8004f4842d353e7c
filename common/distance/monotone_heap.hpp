// The shortest-path searches' priority queue: (key, id) entries popped in (key, id) order, where
// no key pushed is below the last key popped (Dijkstra's keys only grow). A radix heap on the
// keys' bit patterns (non-negative doubles order as their bits do): bucket b holds the entries
// whose key first differs from the last popped key at bit b - 1 from the bottom, so a push is an
// append and an entry moves down at most 64 buckets in all; the entries whose key equals the
// last popped one wait in a small binary heap by id, which keeps the ties' order (the searches
// rely on hub streams, then nodes, then tree boxes popping first at equal keys).
// Ids in [0, tracked) are filed at most once: pushing one already filed with a smaller key
// lowers it (its old entry is dropped where it lies when next met), with a larger key does
// nothing: a search relaxes a node many times before it settles it, and only its lowest entry
// is ever popped.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace fnet {

class MonotoneHeap {
 public:
  using Entry = std::pair<double, std::int64_t>;

  explicit MonotoneHeap(std::size_t tracked = 0) : filed_(tracked, kNotFiled) {}

  bool empty() const { return size_ == 0; }
  void clear() {
    for (std::uint64_t mask = occupied_; mask != 0; mask &= mask - 1) {
      for (const Item& item : buckets_[std::countr_zero(mask)]) forget(item.id);
      buckets_[std::countr_zero(mask)].clear();
    }
    for (const Item& item : ties_) forget(item.id);
    occupied_ = 0;
    ties_.clear();
    size_ = 0;
    last_ = 0;
  }

  // key >= 0. A key below the last one popped (a bound and the value it bounds computed apart
  // can differ by rounding) is filed with the last one's ties and popped with its own key.
  void push(Entry e) {
    if (!(e.first >= 0)) throw std::logic_error("monotone heap: a key below 0");
    const std::uint64_t bits = std::max(std::bit_cast<std::uint64_t>(e.first), last_);
    if (is_tracked(e.second)) {
      double& filed = filed_[static_cast<std::size_t>(e.second)];
      if (filed <= e.first) return;  // false while not filed (NaN)
      if (std::isnan(filed)) ++size_;
      filed = e.first;
    } else {
      ++size_;
    }
    if (bits == last_) {
      ties_.push_back({bits, e.second, e.first});
      std::push_heap(ties_.begin(), ties_.end(), later_id);
      return;
    }
    const int b = bucket_of(bits);
    buckets_[b].push_back({bits, e.second, e.first});
    occupied_ |= std::uint64_t{1} << b;
  }

  // The least entry, removed. Not on an empty heap.
  Entry pop() {
    for (;;) {
      if (ties_.empty()) refill();
      std::pop_heap(ties_.begin(), ties_.end(), later_id);
      const Item top = ties_.back();
      ties_.pop_back();
      if (is_stale(top)) continue;
      if (is_tracked(top.id)) filed_[static_cast<std::size_t>(top.id)] = kNotFiled;
      --size_;
      return {top.key, top.id};
    }
  }

 private:
  struct Item {
    std::uint64_t bits;  // of the key it is filed under
    std::int64_t id;
    double key;  // as pushed
  };
  static bool later_id(const Item& p, const Item& r) { return p.id > r.id; }
  static constexpr double kNotFiled = std::numeric_limits<double>::quiet_NaN();
  bool is_tracked(std::int64_t id) const { return id >= 0 && static_cast<std::size_t>(id) < filed_.size(); }
  bool is_stale(const Item& item) const {
    return is_tracked(item.id) && !(filed_[static_cast<std::size_t>(item.id)] == item.key);
  }
  void forget(std::int64_t id) {
    if (is_tracked(id)) filed_[static_cast<std::size_t>(id)] = kNotFiled;
  }
  int bucket_of(std::uint64_t bits) const { return 64 - std::countl_zero(bits ^ last_); }  // 1..63

  // The ties are empty: the least key moves there from the lowest occupied bucket, whose other
  // entries go to lower buckets (they now differ from the new last key lower down).
  void refill() {
    for (;;) {
      const int b = std::countr_zero(occupied_);
      std::vector<Item>& from = buckets_[b];
      occupied_ &= ~(std::uint64_t{1} << b);
      std::uint64_t least = ~std::uint64_t{0};  // above every key's bits: the sign bit is never set
      for (const Item& item : from)
        if (!is_stale(item)) least = std::min(least, item.bits);
      if (least == ~std::uint64_t{0}) {  // old entries of lowered ids only
        from.clear();
        continue;
      }
      last_ = least;
      moving_.swap(from);
      for (const Item& item : moving_) {
        if (is_stale(item)) continue;
        if (item.bits == last_) {
          ties_.push_back(item);
          continue;
        }
        const int to = bucket_of(item.bits);
        buckets_[to].push_back(item);
        occupied_ |= std::uint64_t{1} << to;
      }
      moving_.clear();
      std::make_heap(ties_.begin(), ties_.end(), later_id);
      return;
    }
  }

  std::vector<Item> buckets_[64];  // 1..63 used: keys are >= 0, their sign bits never differ
  std::vector<Item> moving_;
  std::uint64_t occupied_ = 0;  // bit b: bucket b is not empty
  std::vector<Item> ties_;      // the entries filed under last_, a min-heap by id
  std::uint64_t last_ = 0;      // the bits of the last key popped
  std::size_t size_ = 0;        // entries filed, not counting lowered ones' old entries
  std::vector<double> filed_;   // per tracked id: the key it is filed under, or kNotFiled (NaN)
};

}  // namespace fnet
