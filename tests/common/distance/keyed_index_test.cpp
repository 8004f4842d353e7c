// The hubs' arc streams: KeyedIndex against a std::set of (key, index) under random updates,
// erasures and walks, ties in key included (the walk must give the set's order, which is what the
// searches offered before and what keeps their results unchanged).
#include "common/distance/keyed_index.hpp"

#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

namespace fnet::test {
namespace {

TEST(KeyedIndex, WalksInTheOrderOfASortedSet) {
  std::mt19937_64 rng(1202);
  std::uniform_int_distribution<int> key(0, 12), op(0, 9);
  for (int trial = 0; trial < 40; ++trial) {
    const std::uint32_t size = 1 + static_cast<std::uint32_t>(rng() % 300);
    std::uniform_int_distribution<std::uint32_t> index(0, size - 1);
    KeyedIndex keys(size);
    std::set<KeyedIndex::Entry> reference;
    std::vector<double> key_of(size, -1);  // -1: not filed
    for (int step = 0; step < 3000; ++step) {
      const std::uint32_t i = index(rng);
      const int what = op(rng);
      if (what < 6) {  // file or move
        if (key_of[i] >= 0) reference.erase({key_of[i], i});
        key_of[i] = key(rng) * 0.25;
        reference.insert({key_of[i], i});
        keys.set(i, key_of[i]);
      } else if (what < 9) {
        if (key_of[i] >= 0) reference.erase({key_of[i], i});
        key_of[i] = -1;
        keys.erase(i);
      } else {  // a walk, stopped part way as the searches stop
        const std::size_t stop = rng() % (reference.size() + 1);
        keys.walk_start();
        std::size_t walked = 0;
        for (auto it = reference.begin(); walked < stop; ++it, ++walked) {
          ASSERT_FALSE(keys.walk_done());
          ASSERT_EQ(keys.walk_head(), *it) << "trial " << trial << " step " << step << " entry " << walked;
          keys.walk_next();
        }
        if (stop == reference.size()) {
          EXPECT_TRUE(keys.walk_done());
        }
      }
      ASSERT_EQ(keys.size(), reference.size());
      ASSERT_EQ(keys.contains(i), key_of[i] >= 0);
    }
  }
}

TEST(KeyedIndex, EmptyWalkIsDone) {
  KeyedIndex keys(4);
  keys.walk_start();
  EXPECT_TRUE(keys.walk_done());
  keys.set(2, 1.5);
  keys.erase(2);
  keys.erase(3);  // not filed: nothing
  keys.walk_start();
  EXPECT_TRUE(keys.walk_done());
  EXPECT_FALSE(keys.contains(2));
}

}  // namespace
}  // namespace fnet::test
