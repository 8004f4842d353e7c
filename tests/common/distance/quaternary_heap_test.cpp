// The searches' heap pops its entries in (key, id) order, as std::priority_queue does, ties in key
// included (the searches rely on streams, then nodes, then boxes popping first at equal keys).
#include "common/distance/quaternary_heap.hpp"

#include <functional>
#include <optional>
#include <queue>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace fnet::test {
namespace {

TEST(QuaternaryHeap, PopsInTheOrderOfAPriorityQueue) {
  std::mt19937_64 rng(1201);
  std::uniform_int_distribution<int> key(0, 20), id(-2, 1000), op(0, 2);
  for (int trial = 0; trial < 50; ++trial) {
    QuaternaryHeap heap;
    std::priority_queue<QuaternaryHeap::Entry, std::vector<QuaternaryHeap::Entry>, std::greater<>> reference;
    for (int step = 0; step < 2000; ++step) {
      if (op(rng) == 0 && !reference.empty()) {  // a third of the steps pop, the rest push
        ASSERT_FALSE(heap.empty());
        EXPECT_EQ(heap.pop(), reference.top()) << "trial " << trial << " step " << step;
        reference.pop();
      } else {
        const QuaternaryHeap::Entry e{key(rng) * 0.5, id(rng)};
        heap.push(e);
        reference.push(e);
      }
    }
    while (!reference.empty()) {
      EXPECT_EQ(heap.pop(), reference.top());
      reference.pop();
    }
    EXPECT_TRUE(heap.empty());
  }
}

// Tracked ids (decrease-key): the pops are those of the lazy heap with its stale copies skipped,
// that is the reference queue's pops minus each tracked id's later, larger copies.
TEST(QuaternaryHeap, TrackedIdsPopOnceAtTheirLeastKey) {
  std::mt19937_64 rng(1204);
  std::uniform_int_distribution<int> key(0, 20), id(-3, 60), op(0, 2);
  constexpr std::int64_t kTracked = 40;  // ids 40..60 and the negative ones are untracked
  for (int trial = 0; trial < 50; ++trial) {
    QuaternaryHeap heap(kTracked);
    std::priority_queue<QuaternaryHeap::Entry, std::vector<QuaternaryHeap::Entry>, std::greater<>> reference;
    std::vector<double> best(kTracked, -1);  // a tracked id's least key while filed, -1 if not
    const auto reference_pop = [&]() -> std::optional<QuaternaryHeap::Entry> {
      while (!reference.empty()) {
        const QuaternaryHeap::Entry e = reference.top();
        reference.pop();
        if (e.second < 0 || e.second >= kTracked) return e;
        if (best[e.second] != e.first) continue;  // a stale copy
        best[e.second] = -1;
        return e;
      }
      return std::nullopt;
    };
    for (int step = 0; step < 2000; ++step) {
      if (op(rng) == 0) {
        const auto expected = reference_pop();
        ASSERT_EQ(heap.empty(), !expected) << "trial " << trial << " step " << step;
        if (expected) {
          EXPECT_EQ(heap.pop(), *expected) << "trial " << trial << " step " << step;
        }
      } else {
        const QuaternaryHeap::Entry e{key(rng) * 0.5, id(rng)};
        heap.push(e);
        if (e.second >= 0 && e.second < kTracked) {
          if (best[e.second] >= 0 && best[e.second] <= e.first) continue;
          best[e.second] = e.first;
        }
        reference.push(e);
      }
    }
    while (const auto expected = reference_pop()) EXPECT_EQ(heap.pop(), *expected);
    EXPECT_TRUE(heap.empty());
    heap.push({1.0, 5});
    heap.clear();  // forgets the tracked id's place: it can be filed afresh
    heap.push({3.0, 5});
    EXPECT_EQ(heap.pop(), (QuaternaryHeap::Entry{3.0, 5}));
  }
}

TEST(QuaternaryHeap, ClearEmpties) {
  QuaternaryHeap heap;
  EXPECT_TRUE(heap.empty());
  heap.push({1.0, 2});
  heap.push({0.5, 3});
  heap.clear();
  EXPECT_TRUE(heap.empty());
  heap.push({2.0, 1});
  EXPECT_EQ(heap.pop(), (QuaternaryHeap::Entry{2.0, 1}));
  EXPECT_TRUE(heap.empty());
}

}  // namespace
}  // namespace fnet::test
