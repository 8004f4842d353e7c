// The searches' priority queue against a reference list: entries pop in (key, id) order, a key
// pushed below the last one popped (rounding) pops with that one's ties by id and with its own
// key, tracked ids are filed once (a smaller key lowers them, a larger one changes nothing),
// untracked ids (negative: hub streams; past the tracked range: tree boxes) as often as pushed
// (the searches file each of those at most once at a time, and so does this test).
#include "common/distance/monotone_heap.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace fnet::test {
namespace {

class ReferenceHeap {
 public:
  using Entry = MonotoneHeap::Entry;
  explicit ReferenceHeap(std::int64_t tracked) : tracked_(tracked) {}

  void push(Entry e) {
    const double filed = std::max(e.first, last_);
    if (e.second >= 0 && e.second < tracked_) {
      const auto it = std::find_if(items_.begin(), items_.end(), [&](const Item& i) { return i.id == e.second; });
      if (it != items_.end()) {
        if (it->key <= e.first) return;
        *it = {filed, e.second, e.first};
        return;
      }
    }
    items_.push_back({filed, e.second, e.first});
  }
  std::optional<Entry> pop() {
    if (items_.empty()) return std::nullopt;
    const auto it = std::min_element(items_.begin(), items_.end(), [](const Item& p, const Item& r) {
      return p.filed != r.filed ? p.filed < r.filed : p.id < r.id;
    });
    const Item top = *it;
    items_.erase(it);
    last_ = top.filed;
    return Entry{top.key, top.id};
  }
  double last() const { return last_; }

 private:
  struct Item {
    double filed;
    std::int64_t id;
    double key;
  };
  std::int64_t tracked_;
  std::vector<Item> items_;
  double last_ = 0;
};

TEST(MonotoneHeap, PopsLikeTheReference) {
  std::mt19937_64 rng(1205);
  std::uniform_int_distribution<int> step(0, 12), op(0, 3);
  std::uniform_int_distribution<std::int64_t> tracked_id(0, 39);
  constexpr std::int64_t kTracked = 40;
  for (int trial = 0; trial < 60; ++trial) {
    MonotoneHeap heap(kTracked);
    ReferenceHeap reference(kTracked);
    // Keys spread over many binary orders of magnitude (every bucket), on a grid with ties.
    const double spread = trial % 2 ? 0.25 : 1e-3;
    for (int s = 0; s < 3000; ++s) {
      if (op(rng) == 0) {
        const auto expected = reference.pop();
        ASSERT_EQ(heap.empty(), !expected) << "trial " << trial << " step " << s;
        if (expected) {
          ASSERT_EQ(heap.pop(), *expected) << "trial " << trial << " step " << s;
        }
        continue;
      }
      double key = reference.last() + step(rng) * spread * (1 + (rng() % 7 == 0 ? 1e6 : 0));
      if (rng() % 9 == 0) key = std::nextafter(reference.last(), 0.0);  // rounding below the last
      // Tracked ids two times in three, else a fresh untracked one (a box, or now and then below 0).
      const std::int64_t fresh = rng() % 5 == 0 ? -1 - s : kTracked + s;
      const MonotoneHeap::Entry e{key, rng() % 3 ? tracked_id(rng) : fresh};
      heap.push(e);
      reference.push(e);
    }
    while (const auto expected = reference.pop()) ASSERT_EQ(heap.pop(), *expected);
    EXPECT_TRUE(heap.empty());
  }
}

TEST(MonotoneHeap, ClearForgetsFiledIds) {
  MonotoneHeap heap(8);
  heap.push({2.0, 5});
  heap.push({1.0, 5});  // lowered: the 2.0 entry is dropped
  EXPECT_EQ(heap.pop(), (MonotoneHeap::Entry{1.0, 5}));
  EXPECT_TRUE(heap.empty());
  heap.push({3.0, 5});
  heap.push({4.0, 6});
  heap.clear();  // also the last key: a smaller one may come next
  EXPECT_TRUE(heap.empty());
  heap.push({0.5, 5});
  heap.push({0.5, -1});
  EXPECT_EQ(heap.pop(), (MonotoneHeap::Entry{0.5, -1}));
  EXPECT_EQ(heap.pop(), (MonotoneHeap::Entry{0.5, 5}));
  EXPECT_TRUE(heap.empty());
}

TEST(MonotoneHeap, RejectsNegativeAndNanKeys) {
  MonotoneHeap heap;
  EXPECT_THROW(heap.push({-1.0, 0}), std::logic_error);
  EXPECT_THROW(heap.push({std::nan(""), 0}), std::logic_error);
  EXPECT_TRUE(heap.empty());
}

}  // namespace
}  // namespace fnet::test
