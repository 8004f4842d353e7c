// The searches' heap pops its entries in (key, id) order, as std::priority_queue does, ties in key
// included (the searches rely on streams, then nodes, then boxes popping first at equal keys).
#include "common/distance/quaternary_heap.hpp"

#include <functional>
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
