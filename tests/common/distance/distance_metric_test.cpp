// The metric value type and the one dispatch from it to the distances.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "common/analysis/frame_analysis.hpp"
#include "distance_support.hpp"
#include "distance_test_util.hpp"

namespace fnet::test {
namespace {

TEST(DistanceMetricValue, BottleneckIsTheLimitExponent) {
  const DistanceMetric b = DistanceMetric::bottleneck();
  EXPECT_TRUE(b.is_bottleneck());
  EXPECT_EQ(b.q, std::numeric_limits<double>::infinity());
  EXPECT_EQ(b, DistanceMetric{});
  const DistanceMetric w = DistanceMetric::wasserstein(2.5);
  EXPECT_FALSE(w.is_bottleneck());
  EXPECT_EQ(w.kind, DistanceMetric::Kind::wasserstein);
  EXPECT_EQ(w.q, 2.5);
  EXPECT_NE(w, DistanceMetric::wasserstein(2));
  for (const double bad : {0.0, 0.5, -1.0, std::numeric_limits<double>::infinity(), std::nan("")})
    EXPECT_THROW(DistanceMetric::wasserstein(bad), std::invalid_argument) << bad;
}

TEST(DistanceMetricValue, StoredMetricsAndDispatch) {
  EXPECT_EQ(distance_metric(Metric::bottleneck), DistanceMetric::bottleneck());
  EXPECT_EQ(distance_metric(Metric::wasserstein1), DistanceMetric::wasserstein(1));
  EXPECT_EQ(distance_metric(Metric::wasserstein2), DistanceMetric::wasserstein(2));
  std::mt19937_64 rng(31);
  const Diagram a = random_diagram(rng, 40, 3, false), b = perturbed(rng, a, 0.2);
  for (const EssentialConvention c : kAllConventions) {
    EXPECT_EQ(diagram_distance(a, b, DistanceMetric::bottleneck(), c).value, distance(a, b, 0, c).value);
    for (const double q : {1.0, 2.0, 3.5, 1000.0})
      EXPECT_EQ(diagram_distance(a, b, DistanceMetric::wasserstein(q), c).value, distance(a, b, q, c).value);
    EXPECT_EQ(diagram_distance(a, b, Metric::wasserstein2, c).value, distance(a, b, 2, c).value);
  }
  // delta reaches the bottleneck: a certified interval around the exact value.
  const DistanceResult approx = diagram_distance(a, b, DistanceMetric::bottleneck(), EssentialConvention::floor, 0.5);
  const double exact = distance(a, b, 0, EssentialConvention::floor).value;
  EXPECT_LE(approx.lower, exact);
  EXPECT_GE(approx.upper, exact);
}

}  // namespace
}  // namespace fnet::test
