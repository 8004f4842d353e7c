#include "common/analysis/ensemble_curve.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace fnet {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(EnsembleCurve, BinsOfFixedWidthByHand) {
  const std::vector<CurveSample> s{{0.701, 1.0, 1.0}, {0.705, 2.0, 3.0}, {0.712, 3.0, 2.0}, {0.719, 5.0, 2.0}};
  const auto bins = bin_curve(s, {.width = 0.01});
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_NEAR(bins[0].rho_lo, 0.70, 1e-15);
  EXPECT_NEAR(bins[0].rho_hi, 0.71, 1e-15);
  EXPECT_EQ(bins[0].n, 2u);
  EXPECT_DOUBLE_EQ(bins[0].mean, 2.0);
  ASSERT_TRUE(bins[0].standard_error.has_value());
  EXPECT_DOUBLE_EQ(*bins[0].standard_error, 1.0);  // sd sqrt(2) over sqrt(2)
  EXPECT_DOUBLE_EQ(bins[0].mean_z, 1.5);
  EXPECT_DOUBLE_EQ(bins[0].mean_rho, 0.703);
  EXPECT_DOUBLE_EQ(bins[1].mean, 2.0);
  EXPECT_DOUBLE_EQ(*bins[1].standard_error, 0.0);
  EXPECT_DOUBLE_EQ(bins[1].mean_z, 4.0);
}

TEST(EnsembleCurve, FixedWidthBinsKeepTheirPlaceAsSamplesArrive) {
  std::vector<CurveSample> s{{0.712, 3.0, 2.0}};
  const auto before = bin_curve(s, {.width = 0.01});
  s.push_back({0.795, 3.0, 1.0});
  s.push_back({0.601, 3.0, 1.0});
  const auto after = bin_curve(s, {.width = 0.01});
  ASSERT_EQ(after.size(), 3u);
  EXPECT_EQ(after[1].rho_lo, before[0].rho_lo);
  EXPECT_EQ(after[1].rho_hi, before[0].rho_hi);
  EXPECT_LT(after[0].rho_lo, after[1].rho_lo);
}

TEST(EnsembleCurve, OneValueHasNoErrorInfinityStaysAndNaNIsPassedOver) {
  const std::vector<CurveSample> s{{0.70, 1, 1.0}, {0.81, 1, 1.0}, {0.815, 1, kInf}, {0.9, 1, kNaN}, {kNaN, 1, 1}};
  const auto bins = bin_curve(s, {.width = 0.05});
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_EQ(bins[0].n, 1u);
  EXPECT_FALSE(bins[0].standard_error.has_value());
  EXPECT_EQ(bins[1].n, 2u);
  EXPECT_EQ(bins[1].mean, kInf);
  EXPECT_FALSE(bins[1].standard_error.has_value());
  EXPECT_TRUE(bin_curve(std::vector<CurveSample>{}, {.width = 0.01}).empty());
}

TEST(EnsembleCurve, CountBinsSpanTheRangeWithTheLastOneClosed) {
  const std::vector<CurveSample> s{{0.70, 0, 1}, {0.75, 0, 2}, {0.80, 0, 3}, {0.90, 0, 4}};
  const auto bins = bin_curve(s, {.count = 2});
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_DOUBLE_EQ(bins[0].rho_lo, 0.70);
  EXPECT_NEAR(bins[0].rho_hi, 0.80, 1e-15);
  EXPECT_EQ(bins[0].n, 2u);
  EXPECT_EQ(bins[1].n, 2u);  // 0.80 and the maximum 0.90
  EXPECT_DOUBLE_EQ(bins[1].rho_hi, 0.90);
  const auto one = bin_curve(std::vector<CurveSample>{{0.8, 0, 1}, {0.8, 0, 3}}, {.count = 5});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_DOUBLE_EQ(one[0].mean, 2.0);
}

TEST(EnsembleCurve, ABinningIsAWidthOrACount) {
  const std::vector<CurveSample> s{{0.7, 0, 1}};
  EXPECT_THROW(bin_curve(s, {}), std::invalid_argument);
  EXPECT_THROW(bin_curve(s, {.width = 0.01, .count = 3}), std::invalid_argument);
  EXPECT_THROW(bin_curve(s, {.width = -0.01}), std::invalid_argument);
  EXPECT_THROW(bin_curve(s, {.width = kNaN}), std::invalid_argument);
  EXPECT_THROW(bin_curve(s, {.width = kInf}), std::invalid_argument);
}

// A width so fine that a sample's bin index leaves 64 bits is refused, not cast (undefined).
TEST(EnsembleCurve, AWidthWhoseBinIndicesOverflowIsRefused) {
  const std::vector<CurveSample> s{{0.7, 0, 1}, {-0.2, 0, 2}};
  EXPECT_THROW(bin_curve(s, {.width = 1e-300}), std::invalid_argument);
  EXPECT_EQ(bin_curve(s, {.width = 1e-12}).size(), 2u);
}

// Against a reference written from the definitions: every sample tested against every bin's
// bounds, sums in long double.
TEST(EnsembleCurve, RandomEnsemblesAgainstADirectComputation) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> rho(0.63, 0.90), z(0, 4.5), value(0, 1e3);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<CurveSample> s(20 * 100);
    for (CurveSample& x : s) x = {rho(rng), z(rng), value(rng) * value(rng)};
    const double width = 0.005 * (1 + trial % 4);
    const auto bins = bin_curve(s, {.width = width});
    std::size_t total = 0;
    for (const CurveBin& b : bins) {
      long double sum = 0, sum_z = 0;
      std::vector<double> in;
      for (const CurveSample& x : s)
        if (x.rho >= b.rho_lo && x.rho < b.rho_hi) in.push_back(x.value), sum += x.value, sum_z += x.z;
      ASSERT_EQ(in.size(), b.n) << "bin at " << b.rho_lo;
      const long double mean = sum / in.size();
      long double squares = 0;
      for (const double v : in) squares += (v - mean) * (v - mean);
      EXPECT_NEAR(b.mean, static_cast<double>(mean), 1e-12 * static_cast<double>(mean));
      EXPECT_NEAR(b.mean_z, static_cast<double>(sum_z / in.size()), 1e-12);
      ASSERT_TRUE(b.standard_error.has_value());
      const double se = static_cast<double>(std::sqrt(squares / (in.size() - 1)) / std::sqrt((long double)in.size()));
      EXPECT_NEAR(*b.standard_error, se, 1e-10 * se);
      total += b.n;
    }
    EXPECT_EQ(total, s.size());
  }
}

TEST(EnsembleCurve, RatioOfTheBinMeans) {
  const std::vector<CurveSample> db{{0.701, 1, 1}, {0.705, 1, 3}, {0.751, 1, 0}};
  const std::vector<CurveSample> w2{{0.701, 1, 4}, {0.705, 1, 4}, {0.751, 1, 0}, {0.801, 1, 1}};
  const auto ratio = ratio_curve(bin_curve(db, {.width = 0.05}), bin_curve(w2, {.width = 0.05}));
  ASSERT_EQ(ratio.size(), 2u);           // the 0.80 bin has no numerator
  EXPECT_DOUBLE_EQ(ratio[0].mean, 0.5);  // mean 2 over mean 4, not the mean of the ratios 1/4, 3/4
  EXPECT_EQ(ratio[0].n, 2u);
  EXPECT_FALSE(ratio[0].standard_error.has_value());
  EXPECT_TRUE(std::isnan(ratio[1].mean));  // 0 / 0
}

}  // namespace
}  // namespace fnet
