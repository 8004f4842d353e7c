#include "common/analysis/jamming.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace fnet {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(Jamming, LinearContactNumberCrossesWhereTheLineDoes) {
  // Z = 40 (rho - 0.74) reaches 3 at rho = 0.815 exactly (in exact arithmetic).
  std::vector<double> rho, z;
  for (int k = 0; k <= 20; ++k) {
    rho.push_back(0.70 + 0.01 * k);
    z.push_back(std::max(0.0, 40 * (rho.back() - 0.74)));
  }
  const auto j = jamming_density(rho, z);
  ASSERT_TRUE(j.has_value());
  EXPECT_NEAR(*j, 0.815, 1e-12);
}

TEST(Jamming, FirstCrossingCountsNotALaterOne) {
  // Z reaches 3, falls back (a rearrangement) and reaches it again: the first crossing is rho_J.
  const std::vector<double> rho{0.80, 0.81, 0.82, 0.83, 0.84}, z{2.0, 4.0, 2.5, 3.5, 4.0};
  EXPECT_NEAR(*jamming_density(rho, z), 0.805, 1e-12);
}

TEST(Jamming, ExactlyThreeIsReached) {
  const std::vector<double> rho{0.80, 0.81, 0.82}, z{2.0, 3.0, 3.0};
  EXPECT_DOUBLE_EQ(*jamming_density(rho, z), 0.81);
}

TEST(Jamming, NeverReachedIsNoneAndAlreadyJammedIsTheFirstFrame) {
  EXPECT_FALSE(jamming_density(std::vector<double>{0.7, 0.8}, std::vector<double>{1.0, 2.9}).has_value());
  EXPECT_FALSE(jamming_density(std::vector<double>{}, std::vector<double>{}).has_value());
  EXPECT_DOUBLE_EQ(*jamming_density(std::vector<double>{0.85, 0.86}, std::vector<double>{3.2, 3.4}), 0.85);
  EXPECT_DOUBLE_EQ(*jamming_density(std::vector<double>{0.85}, std::vector<double>{3.0}), 0.85);
}

TEST(Jamming, NonFiniteFramesArePassedOver) {
  const std::vector<double> rho{0.80, kNaN, 0.82}, z{2.0, 10.0, 4.0};
  EXPECT_NEAR(*jamming_density(rho, z), 0.81, 1e-12);
  EXPECT_THROW(jamming_density(std::vector<double>{0.8}, std::vector<double>{}), std::invalid_argument);
}

TEST(Jamming, AnotherThresholdForFrictionlessComparisons) {
  const std::vector<double> rho{0.80, 0.84}, z{3.0, 5.0};
  EXPECT_NEAR(*jamming_density(rho, z, 4.0), 0.82, 1e-12);
}

}  // namespace
}  // namespace fnet
