// The 2-d tree's k-nearest query against brute force: the k smallest L-infinity distances, nearest
// first, each point once, on points with many exact ties (a coarse grid, duplicates, a common
// death line), with and without a tie-breaking salt, and for k past the number of points.
#include "common/distance/linf_kdtree.hpp"

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

namespace fnet::test {
namespace {

TEST(LinfKdTree, NearestAreTheKSmallestDistances) {
  std::mt19937_64 rng(1203);
  std::uniform_int_distribution<int> grid(0, 9);
  for (int trial = 0; trial < 60; ++trial) {
    const std::size_t n = 1 + rng() % 200;
    const bool on_line = trial % 3 == 0;
    std::vector<PlanePoint> points;
    for (std::size_t k = 0; k < n; ++k) points.push_back({grid(rng) * 0.5, on_line ? 0.0 : grid(rng) * 0.5});
    const LinfKdTree tree(points);
    std::vector<std::uint32_t> out;
    for (int query = 0; query < 30; ++query) {
      const PlanePoint q{grid(rng) * 0.5 + 0.25 * (query % 2), grid(rng) * 0.5};
      const std::size_t k = 1 + rng() % 8;
      const std::uint64_t salt = query % 3 == 0 ? 0 : rng();
      tree.nearest(q, k, out, salt);
      std::vector<double> expected;
      for (const PlanePoint p : points) expected.push_back(linf_distance(p, q));
      std::sort(expected.begin(), expected.end());
      expected.resize(std::min(k, n));
      ASSERT_EQ(out.size(), expected.size()) << "trial " << trial << " query " << query;
      EXPECT_EQ(std::set<std::uint32_t>(out.begin(), out.end()).size(), out.size()) << "a point twice";
      for (std::size_t r = 0; r < out.size(); ++r)
        EXPECT_EQ(linf_distance(points[out[r]], q), expected[r])
            << "trial " << trial << " query " << query << " rank " << r;
    }
  }
}

TEST(LinfKdTree, NearestOnAnEmptyTreeIsEmpty) {
  const LinfKdTree tree(std::vector<PlanePoint>{});
  std::vector<std::uint32_t> out{7};
  tree.nearest({0, 0}, 3, out, 5);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace fnet::test
