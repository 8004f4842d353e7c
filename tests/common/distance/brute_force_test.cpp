// Every metric and every convention against all matchings of small diagrams.
#include <gtest/gtest.h>

#include "distance_support.hpp"
#include "distance_test_util.hpp"

namespace fnet::test {
namespace {

TEST(DistanceBruteForce, SmallRandomDiagramsAllMetricsAllConventions) {
  std::mt19937_64 rng(20240601);
  std::uniform_int_distribution<std::size_t> size(0, 5);
  int checked = 0, infinite = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const bool grid = trial % 2 == 0;  // grids make ties and duplicate points
    const Diagram a = random_diagram(rng, size(rng), 3, grid);
    const Diagram b = trial % 3 == 0 ? perturbed(rng, a, 0.3) : random_diagram(rng, size(rng), 3, grid);
    if (a.size() > 6 || b.size() > 6) continue;
    for (const EssentialConvention c : kAllConventions) {
      for (const double q : {0.0, 1.0, 2.0, 1.5, 3.0}) {
        const double expected = brute_force_distance(a, b, q, c);
        const DistanceResult got = distance(a, b, q, c);
        ASSERT_TRUE(close(got.value, expected, 1e-12))
            << label(q, c) << " trial " << trial << ": got " << got.value << " expected " << expected;
        ASSERT_EQ(got.infinite, std::isinf(expected));
        ASSERT_EQ(got.lower, got.value);
        ASSERT_EQ(got.upper, got.value);
        ASSERT_TRUE(got.exact);
        ++checked;
        infinite += got.infinite;
      }
    }
  }
  EXPECT_GT(checked, 4000);
  EXPECT_GT(infinite, 100);  // separate with differing counts was exercised
}

}  // namespace
}  // namespace fnet::test
