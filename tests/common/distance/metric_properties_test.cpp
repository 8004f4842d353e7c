// Metric properties on random inputs: identity, symmetry, triangle inequality, d_B <= d_Wq,
// d_Wq non-increasing in q.
#include <gtest/gtest.h>

#include "distance_support.hpp"
#include "distance_test_util.hpp"

namespace fnet::test {
namespace {

constexpr double kRel = 1e-11;

TEST(DistanceProperties, RandomTriples) {
  std::mt19937_64 rng(424242);
  std::uniform_int_distribution<std::size_t> size(0, 120);
  const EssentialConvention conventions[] = {EssentialConvention::floor, EssentialConvention::sentinel};
  for (int trial = 0; trial < 120; ++trial) {
    const bool grid = trial % 3 == 0;
    const Diagram x = random_diagram(rng, size(rng), 4, grid);
    const Diagram y = trial % 2 ? perturbed(rng, x, 0.2) : random_diagram(rng, size(rng), 4, grid);
    const Diagram z = perturbed(rng, y, 0.3);
    for (const EssentialConvention c : conventions) {
      double previous = std::numeric_limits<double>::infinity();
      const double db = distance(x, y, 0, c).value;
      for (const double q : {0.0, 1.0, 1.5, 2.0, 3.0, 6.0}) {
        const double xy = distance(x, y, q, c).value, yx = distance(y, x, q, c).value;
        const double xz = distance(x, z, q, c).value, yz = distance(y, z, q, c).value;
        ASSERT_EQ(distance(x, x, q, c).value, 0) << label(q, c);
        ASSERT_TRUE(close(xy, yx, kRel)) << label(q, c) << " trial " << trial << ": " << xy << " vs " << yx;
        ASSERT_LE(xz, (xy + yz) * (1 + kRel)) << label(q, c) << " trial " << trial;
        if (q > 0) {
          ASSERT_LE(db, xy * (1 + kRel)) << label(q, c) << " trial " << trial;
          ASSERT_LE(xy, previous * (1 + kRel)) << label(q, c) << " trial " << trial;
          previous = xy;
        }
      }
    }
  }
}

TEST(DistanceProperties, FloorIsBelowSentinelOnRattlers) {
  // Rattlers (0, -1) cost nothing under floor and 0.5 each under sentinel.
  const Diagram a = {{2, 1}, {0, -1}, {0, -1}}, b = {{2, 1}};
  EXPECT_EQ(distance(a, b, 0, EssentialConvention::floor).value, 0);
  EXPECT_EQ(distance(a, b, 0, EssentialConvention::sentinel).value, 0.5);
  EXPECT_EQ(distance(a, b, 1, EssentialConvention::sentinel).value, 1.0);
  EXPECT_TRUE(distance(a, b, 1, EssentialConvention::separate).infinite);
}

}  // namespace
}  // namespace fnet::test
