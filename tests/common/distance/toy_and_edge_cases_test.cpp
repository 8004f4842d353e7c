// The paper's toy example and the inputs that break the anchors (Hera, POT).
#include <chrono>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "common/codec/distance_json.hpp"
#include "distance_support.hpp"
#include "distance_test_util.hpp"

namespace fnet::test {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(DistanceToy, PaperFigure5) {
  // PD(f) = {(5, -1)}; PD(g) = {(3, -1)} + 7 x (1, 0). The paper prints d_W2 ~ 2.6; its own
  // definition gives sqrt(2^2 + 7 * 0.5^2) = sqrt(5.75), as README says.
  const Diagram f = {{5, -1}};
  Diagram g = {{3, -1}};
  for (int k = 0; k < 7; ++k) g.push_back({1, 0});
  for (const EssentialConvention c : kAllConventions) {
    EXPECT_DOUBLE_EQ(distance(f, g, 0, c).value, 2) << to_string(c);
    EXPECT_DOUBLE_EQ(distance(f, g, 1, c).value, 5.5) << to_string(c);
    EXPECT_DOUBLE_EQ(distance(f, g, 2, c).value, std::sqrt(5.75)) << to_string(c);
    EXPECT_DOUBLE_EQ(distance(g, f, 2, c).value, std::sqrt(5.75)) << to_string(c);
  }
}

TEST(DistanceEdge, EmptyVersusEmptyAndVersusManyPoints) {
  std::mt19937_64 rng(7);
  const Diagram empty, big = random_diagram(rng, 10000, 5, false);
  for (const EssentialConvention c : {EssentialConvention::floor, EssentialConvention::sentinel}) {
    for (const double q : {0.0, 1.0, 2.0}) {
      EXPECT_EQ(distance(empty, empty, q, c).value, 0);
      EXPECT_TRUE(close(distance(empty, big, q, c).value, brute_force_distance(empty, big, q, c), 1e-12));
      EXPECT_TRUE(close(distance(big, empty, q, c).value, brute_force_distance(big, empty, q, c), 1e-12));
    }
  }
}

TEST(DistanceEdge, IdenticalDiagramsAreExactlyZero) {
  std::mt19937_64 rng(8);
  Diagram a = random_diagram(rng, 3000, 5, false);
  Diagram shuffled = a;
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  for (const EssentialConvention c : kAllConventions)
    for (const double q : {0.0, 1.0, 2.0, 2.5}) {
      const DistanceResult r = distance(a, shuffled, q, c);
      EXPECT_EQ(r.value, 0) << label(q, c);
      EXPECT_EQ(r.upper, 0);
    }
}

TEST(DistanceEdge, ThousandsOfDuplicates) {
  Diagram a(3000, {2.0, 1.0}), b(2500, {2.0, 1.0});
  for (int k = 0; k < 500; ++k) b.push_back({2.25, 1.0});
  // 2500 pair at 0; 500 (2,1) vs (2.25,1): 0.25 each, cheaper than 0.5 + 0.625 via the diagonal.
  EXPECT_DOUBLE_EQ(distance(a, b, 0, EssentialConvention::floor).value, 0.25);
  EXPECT_DOUBLE_EQ(distance(a, b, 1, EssentialConvention::floor).value, 125);
  EXPECT_DOUBLE_EQ(distance(a, b, 2, EssentialConvention::floor).value, std::sqrt(500 * 0.0625));
  Diagram c(3000, {2.0, 1.0});
  EXPECT_EQ(distance(a, c, 1, EssentialConvention::floor).value, 0);
  c.push_back({2.0, 1.0});
  EXPECT_DOUBLE_EQ(distance(a, c, 1, EssentialConvention::floor).value, 0.5);
}

TEST(DistanceEdge, PointsOnAndAHairOffTheDiagonal) {
  // Hera's bottleneck throws on points lying on the diagonal.
  const Diagram on = {{1, 1}, {2, 2}, {3, 3}}, off = {{1 + 1e-15, 1}, {2, 2 - 4e-16}};
  EXPECT_EQ(distance(on, Diagram{}, 0, EssentialConvention::floor).value, 0);
  EXPECT_EQ(distance(on, on, 1, EssentialConvention::floor).value, 0);
  for (const double q : {0.0, 1.0, 2.0})
    EXPECT_TRUE(close(distance(on, off, q, EssentialConvention::floor).value,
                      brute_force_distance(on, off, q, EssentialConvention::floor), 1e-12));
  std::mt19937_64 rng(9);
  Diagram hair, hair2;
  std::uniform_real_distribution<double> u(0, 10);
  for (int k = 0; k < 2000; ++k) {
    const double x = u(rng);
    hair.push_back({std::nextafter(x, 20.0), x});
    hair2.push_back({x + 1e-13 * u(rng), x});
  }
  for (const double q : {0.0, 1.0, 2.0}) {
    const DistanceResult r = distance(hair, hair2, q, EssentialConvention::floor);
    EXPECT_TRUE(std::isfinite(r.value));
    const double to_diagonal = distance(hair, Diagram{}, q, EssentialConvention::floor).value +
                               distance(Diagram{}, hair2, q, EssentialConvention::floor).value;
    EXPECT_GT(r.value, 0);
    EXPECT_LE(r.value, to_diagonal * (1 + 1e-12));
  }
}

TEST(DistanceEdge, SeparateWithDifferentEssentialCountsIsInfinite) {
  // Hera's Wasserstein never returns when one diagram holds only essential points and the other
  // only finite ones.
  const Diagram essential_only = {{1, -1}, {2, -1}, {0.5, -1}}, finite_only = {{1, 0.5}, {2, 1}};
  for (const double q : {0.0, 1.0, 2.0, 3.5}) {
    const auto start = std::chrono::steady_clock::now();
    const DistanceResult r = distance(essential_only, finite_only, q, EssentialConvention::separate);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    EXPECT_TRUE(r.infinite);
    EXPECT_EQ(r.value, kInf);
    EXPECT_FALSE(r.reason.empty());
    const nlohmann::json j = to_json(r);
    EXPECT_TRUE(j["value"].is_null());
    EXPECT_EQ(j["infinite"], true);
    EXPECT_TRUE(j["reason"].is_string());
  }
  // Same counts: finite, and the essentials are matched by sorted birth.
  const Diagram e2 = {{1.5, -1}, {0.25, -1}, {2, -1}};
  EXPECT_DOUBLE_EQ(distance(essential_only, e2, 0, EssentialConvention::separate).value, 0.5);
  EXPECT_DOUBLE_EQ(distance(essential_only, e2, 1, EssentialConvention::separate).value, 0.25 + 0.5 + 0);
}

TEST(DistanceEdge, TinyValuesAndScaleInvariance) {
  // Hera's bottleneck returns 0 and POT's exact W2 is off by > 10x when values are ~1e-10.
  std::mt19937_64 rng(10);
  const Diagram a = random_diagram(rng, 300, 3, false), b = perturbed(rng, a, 0.05);
  for (const EssentialConvention c : {EssentialConvention::floor, EssentialConvention::separate}) {
    Diagram bb = b;
    if (c == EssentialConvention::separate) {  // equal essential counts, or everything is +inf
      bb.erase(std::remove_if(bb.begin(), bb.end(), [](const PersistencePoint& p) { return p.death == -1; }), bb.end());
      for (const PersistencePoint& p : a)
        if (p.death == -1) bb.push_back({p.birth * 1.01, -1});
    }
    for (const double q : {0.0, 1.0, 2.0, 1.5}) {
      const double base = distance(a, bb, q, c).value;
      ASSERT_GT(base, 0);
      for (const double s : {1e-12, 1e-10, 3.7e-7, 0.3, 1024.0, 12345.678, 1e6}) {
        const double got = distance(scaled(a, s), scaled(bb, s), q, c).value;
        EXPECT_TRUE(close(got, s * base, 1e-12)) << label(q, c) << " scale " << s << ": " << got << " vs " << s * base;
      }
      // Powers of two rescale exactly.
      EXPECT_EQ(distance(scaled(a, 0x1p-40), scaled(bb, 0x1p-40), q, c).value, std::ldexp(base, -40));
    }
  }
}

TEST(DistanceEdge, ValuesSpanningTwelveToSixOrdersOfMagnitude) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> e(-12, 6), u(0, 1);
  Diagram a;
  for (int k = 0; k < 6; ++k) {
    const double b = std::pow(10.0, e(rng));
    a.push_back({b, b * u(rng)});
  }
  Diagram b = a;
  for (auto& p : b) p.birth *= 1 + 0.1 * u(rng);
  b.push_back({1e-12, 0});
  for (const EssentialConvention c : kAllConventions)
    for (const double q : {0.0, 1.0, 2.0})
      EXPECT_TRUE(close(distance(a, b, q, c).value, brute_force_distance(a, b, q, c), 1e-12)) << label(q, c);
}

TEST(DistanceEdge, RejectsBadParameters) {
  const Diagram a = {{1, 0}};
  EXPECT_THROW(wasserstein_distance(a, a, {.q = 0.5}), std::invalid_argument);
  EXPECT_THROW(wasserstein_distance(a, a, {.q = std::numeric_limits<double>::infinity()}), std::invalid_argument);
  EXPECT_THROW(wasserstein_distance(a, a, {.q = 1, .delta = -1}), std::invalid_argument);
  EXPECT_THROW(bottleneck_distance(a, a, {.relative_error = -0.1}), std::invalid_argument);
  const Diagram nan = {{std::nan(""), 0}};
  EXPECT_THROW(bottleneck_distance(nan, a), std::invalid_argument);
}

}  // namespace
}  // namespace fnet::test
