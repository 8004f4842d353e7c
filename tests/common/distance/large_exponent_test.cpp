// Large exponents, where q-th powers of costs leave the range of doubles: d_Wq for q up to 1e6
// against the brute force (which sums the powers relative to their largest term in long double),
// at 1e-10 and 1e6 scale too; d_B <= d_Wq <= N^(1/q) d_B to the last bit; d_Wq non-increasing in q
// and down to d_B.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "distance_support.hpp"
#include "distance_test_util.hpp"

namespace fnet::test {
namespace {

constexpr double kExponents[] = {1, 1.5, 2, 3, 10, 100, 1000, 1e4, 1e6};

TEST(DistanceLargeExponent, SmallDiagramsAgainstBruteForceAtThreeScales) {
  std::mt19937_64 rng(1000);
  std::uniform_int_distribution<std::size_t> size(0, 5);
  int checked = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const bool grid = trial % 2 == 0;
    const Diagram a = random_diagram(rng, size(rng), 3, grid);
    const Diagram b = trial % 3 == 0 ? perturbed(rng, a, 0.3) : random_diagram(rng, size(rng), 3, grid);
    for (const EssentialConvention c : kAllConventions)
      for (const double scale : {1.0, 1e-10, 1e6}) {
        const Diagram sa = scaled(a, scale), sb = scaled(b, scale);
        for (const double q : {1.0, 2.0, 10.0, 100.0, 1000.0, 1e6}) {
          const double expected = brute_force_distance(sa, sb, q, c);
          const DistanceResult got = distance(sa, sb, q, c);
          ASSERT_TRUE(close(got.value, expected, 1e-12)) << label(q, c) << " scale " << scale << " trial " << trial
                                                         << ": got " << got.value << " expected " << expected;
          ASSERT_EQ(got.lower, got.value);
          ASSERT_EQ(got.upper, got.value);
          ++checked;
        }
      }
  }
  EXPECT_GT(checked, 6000);
}

// Every term of a matching is >= d_B for one of them, and the bottleneck matching has at most N
// terms, each <= d_B: so d_B <= d_Wq <= N^(1/q) d_B, and d_Wq falls to d_B as q grows.
void expect_between_bottleneck_and_root(const Diagram& a, const Diagram& b, EssentialConvention c,
                                        const std::string& what) {
  const double bottleneck = distance(a, b, 0, c).value;
  ASSERT_GT(bottleneck, 0) << what;
  const auto terms = static_cast<double>(a.size() + b.size());
  double previous = std::numeric_limits<double>::infinity();
  for (const double q : kExponents) {
    WassersteinStats st;
    const double value = wasserstein_distance(a, b, {.q = q, .essential = c}, &st).value;
    EXPECT_GE(value, bottleneck) << what << " " << label(q, c);
    EXPECT_LE(value, bottleneck * std::pow(terms, 1 / q) * (1 + 1e-12)) << what << " " << label(q, c);
    EXPECT_LE(value, previous * (1 + 1e-12)) << what << " " << label(q, c) << ": not below the smaller exponent's";
    EXPECT_TRUE(close(st.dual_lower, value, 1e-11)) << what << " " << label(q, c) << ": dual bound " << st.dual_lower
                                                    << " value " << value << " simplex " << st.network_simplex;
    previous = value;
  }
}

TEST(DistanceLargeExponent, BetweenBottleneckAndItsRootOnRandomPairs) {
  std::mt19937_64 rng(1001);
  std::uniform_int_distribution<std::size_t> size(1, 150);
  for (int trial = 0; trial < 40; ++trial) {
    const Diagram a = random_diagram(rng, size(rng), 4, trial % 4 == 0);
    const Diagram b = trial % 2 ? perturbed(rng, a, 0.05) : random_diagram(rng, size(rng), 4, trial % 4 == 0);
    if (bottleneck_distance(a, b).value == 0) continue;
    for (const double scale : {1.0, 1e-10, 1e6})
      for (const EssentialConvention c : {EssentialConvention::floor, EssentialConvention::sentinel})
        expect_between_bottleneck_and_root(scaled(a, scale), scaled(b, scale), c,
                                           "trial " + std::to_string(trial) + " scale " + std::to_string(scale));
  }
}

TEST(DistanceLargeExponent, BetweenBottleneckAndItsRootOnLammpsFrames) {
  for (const bool tangential : {false, true}) {
    const FrameDiagramsPair f8 = lammps_diagrams(8, tangential), f9 = lammps_diagrams(9, tangential);
    const std::string force = tangential ? "tangential " : "normal ";
    expect_between_bottleneck_and_root(f8.pd0, f9.pd0, EssentialConvention::floor, force + "pd0 8->9");
    expect_between_bottleneck_and_root(f8.pd1, f9.pd1, EssentialConvention::floor, force + "pd1 8->9");
  }
}

// The q-th power of a tiny difference beside a huge persistence underflows in any unit of length
// near the largest persistence, for q = 1 and 2 too.
TEST(DistanceLargeExponent, TinyDifferenceBesideHugePersistence) {
  const Diagram big_a = {{1e300, 0}, {1e-30, 0}}, big_b = {{1e300, 0}};
  const Diagram unit_a = {{1, 0}, {1e-200, 0}}, unit_b = {{1, 0}};
  for (const auto& [a, b] : {std::pair{big_a, big_b}, std::pair{unit_a, unit_b}})
    for (const double q : {1.0, 2.0, 3.0, 1000.0}) {
      const double expected = brute_force_distance(a, b, q, EssentialConvention::floor);
      const double got = distance(a, b, q, EssentialConvention::floor).value;
      EXPECT_TRUE(close(got, expected, 1e-12)) << "q=" << q << ": got " << got << " expected " << expected;
      EXPECT_GE(got, distance(a, b, 0, EssentialConvention::floor).value) << "q=" << q;
    }
}

}  // namespace
}  // namespace fnet::test
