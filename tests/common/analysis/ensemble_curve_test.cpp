#include "common/analysis/ensemble_curve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace fnet {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Two runs in the first bin: run 1's two frames count once, through their mean.
TEST(EnsembleCurve, BinsOfFixedWidthByHand) {
  const std::vector<CurveSample> s{
      {0.701, 1.0, 1.0, 0}, {0.705, 2.0, 3.0, 1}, {0.708, 4.0, 5.0, 1}, {0.712, 3.0, 2.0, 0}, {0.719, 5.0, 2.0, 0}};
  const auto bins = bin_curve(s, {.width = 0.01});
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_NEAR(bins[0].rho_lo, 0.70, 1e-15);
  EXPECT_NEAR(bins[0].rho_hi, 0.71, 1e-15);
  EXPECT_EQ(bins[0].n, 3u);
  EXPECT_EQ(bins[0].runs, 2u);
  EXPECT_DOUBLE_EQ(bins[0].mean, 2.5);  // runs' means 1 and 4 (the three frames pooled: 3)
  ASSERT_TRUE(bins[0].standard_error.has_value());
  EXPECT_DOUBLE_EQ(*bins[0].standard_error, 1.5);  // sd of 1, 4: sqrt(4.5), over sqrt(2)
  EXPECT_DOUBLE_EQ(bins[0].mean_z, 2.0);           // runs' means 1 and 3
  EXPECT_DOUBLE_EQ(bins[0].mean_rho, (0.701 + 0.7065) / 2);
  // One run: its mean, and no standard error however many frames it has there.
  EXPECT_EQ(bins[1].n, 2u);
  EXPECT_EQ(bins[1].runs, 1u);
  EXPECT_DOUBLE_EQ(bins[1].mean, 2.0);
  EXPECT_FALSE(bins[1].standard_error.has_value());
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
  const std::vector<CurveSample> s{{0.70, 1, 1.0, 0}, {0.81, 1, 1.0, 0}, {0.815, 1, kInf, 1},
                                   {0.82, 1, 2.0, 1}, {0.9, 1, kNaN, 2}, {kNaN, 1, 1, 2}};
  const auto bins = bin_curve(s, {.width = 0.05});
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_EQ(bins[0].n, 1u);
  EXPECT_EQ(bins[0].runs, 1u);
  EXPECT_FALSE(bins[0].standard_error.has_value());
  // Run 1's mean is +inf, so is the bin's; run 2 had only NaN and counts nowhere.
  EXPECT_EQ(bins[1].n, 3u);
  EXPECT_EQ(bins[1].runs, 2u);
  EXPECT_EQ(bins[1].mean, kInf);
  EXPECT_FALSE(bins[1].standard_error.has_value());
  EXPECT_TRUE(bin_curve(std::vector<CurveSample>{}, {.width = 0.01}).empty());
  EXPECT_TRUE(bin_curve(std::vector<CurveSample>{{0.8, 1, kNaN, 0}}, {.count = 2}).empty());
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

// A bin as the definitions give it, from scratch: which samples lie within its reported edges
// (closed at the top for the last bin of a count binning), each run's mean over them in long
// double, then the mean over the runs and the standard error across the runs' means.
struct Expected {
  std::size_t n = 0, runs = 0;
  long double mean = 0, rho = 0, z = 0;
  std::optional<long double> se;
};

Expected recompute(const std::vector<CurveSample>& s, const CurveBin& b, bool closed) {
  struct Run {
    long double rho = 0, z = 0, value = 0;
    std::size_t n = 0;
  };
  std::map<std::size_t, Run> runs;
  Expected e;
  for (const CurveSample& x : s) {
    if (std::isnan(x.value) || !std::isfinite(x.rho)) continue;
    if (x.rho < b.rho_lo || x.rho > b.rho_hi || (x.rho == b.rho_hi && !closed)) continue;
    Run& r = runs[x.run];
    r.rho += x.rho, r.z += x.z, r.value += x.value, ++r.n, ++e.n;
  }
  e.runs = runs.size();
  if (e.runs == 0) return e;
  std::vector<long double> means;
  for (const auto& [id, r] : runs) {
    means.push_back(r.value / r.n);
    e.mean += means.back(), e.rho += r.rho / r.n, e.z += r.z / r.n;
  }
  e.mean /= e.runs, e.rho /= e.runs, e.z /= e.runs;
  if (e.runs >= 2 && std::isfinite(e.mean)) {
    long double squares = 0;
    for (const long double m : means) squares += (m - e.mean) * (m - e.mean);
    e.se = std::sqrt(squares / (e.runs - 1)) / std::sqrt(static_cast<long double>(e.runs));
  }
  return e;
}

// Random ensembles: 1 to 6 runs of different lengths (so runs have different counts per bin, and
// some bins have one run), samples placed exactly on bin edges and one ulp either side, NaN
// values, and now and then a run with an infinite value. Every bin against recompute(), and every
// usable sample in exactly one bin.
TEST(EnsembleCurve, RandomEnsemblesAgainstADirectComputation) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> rho(0.63, 0.90), z(0, 4.5), value(0, 1e3), unit(0, 1);
  std::size_t ties = 0, single = 0, several = 0, infinite = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const bool by_count = trial % 3 == 2;
    const RhoBinning binning = by_count ? RhoBinning{.count = static_cast<std::size_t>(3 + trial % 17)}
                                        : RhoBinning{.width = 0.003 * (1 + trial % 7)};
    // A count binning spans [0.63, 0.90] exactly: the first and last samples pin the range.
    const double step = by_count ? (0.90 - 0.63) / static_cast<double>(binning.count) : binning.width;
    const auto edge = [&](std::int64_t k) { return (by_count ? 0.63 : 0.0) + static_cast<double>(k) * step; };
    const std::int64_t first = by_count ? 0 : static_cast<std::int64_t>(0.63 / step) + 1;
    const std::int64_t last =
        by_count ? static_cast<std::int64_t>(binning.count) - 1 : static_cast<std::int64_t>(0.9 / step);
    std::uniform_int_distribution<std::int64_t> edges(first, last);
    std::vector<CurveSample> s;
    if (by_count) s.push_back({0.63, 1, 1, 0}), s.push_back({0.90, 2, 2, 0});
    const std::size_t runs = 1 + trial % 6;
    for (std::size_t run = 0; run < runs; ++run) {
      const std::size_t frames = std::uniform_int_distribution<std::size_t>(1, 120)(rng);
      for (std::size_t f = 0; f < frames; ++f) {
        CurveSample x{rho(rng), z(rng), value(rng) * value(rng), run * 7 + 3};  // run indices need not be 0, 1, ...
        const double u = unit(rng);
        if (u < 0.1) {
          x.rho = edge(edges(rng));
          if (u < 0.03) x.rho = std::nextafter(x.rho, 0.0);
          if (u > 0.07) x.rho = std::nextafter(x.rho, 1.0);
        } else if (u < 0.13) {
          x.value = kNaN;
        } else if (u < 0.134 && trial % 5 == 0) {
          x.value = kInf;
        }
        s.push_back(x);
      }
    }
    std::shuffle(s.begin(), s.end(), rng);  // runs interleaved, as members arrive
    const auto bins = bin_curve(s, binning);
    std::size_t total = 0;
    for (std::size_t k = 0; k < bins.size(); ++k) {
      const CurveBin& b = bins[k];
      SCOPED_TRACE("trial " + std::to_string(trial) + ", bin at " + std::to_string(b.rho_lo));
      if (k > 0) {
        ASSERT_LE(bins[k - 1].rho_hi, b.rho_lo);
      }
      const Expected e = recompute(s, b, by_count && k + 1 == bins.size());
      ASSERT_EQ(b.n, e.n);
      ASSERT_EQ(b.runs, e.runs);
      ASSERT_GE(e.runs, 1u);
      EXPECT_NEAR(b.mean_rho, static_cast<double>(e.rho), 1e-14);
      EXPECT_NEAR(b.mean_z, static_cast<double>(e.z), 1e-13);
      if (std::isinf(e.mean)) {
        EXPECT_EQ(b.mean, kInf);
        ++infinite;
      } else {
        EXPECT_NEAR(b.mean, static_cast<double>(e.mean), 1e-12 * static_cast<double>(e.mean));
      }
      ASSERT_EQ(b.standard_error.has_value(), e.se.has_value());
      if (e.se) {
        EXPECT_NEAR(*b.standard_error, static_cast<double>(*e.se), 1e-10 * static_cast<double>(*e.se));
      }
      (e.runs == 1 ? single : several)++;
      total += b.n;
    }
    std::size_t usable = 0;
    for (const CurveSample& x : s) usable += !std::isnan(x.value);
    EXPECT_EQ(total, usable) << "trial " << trial;
    for (const CurveSample& x : s)
      for (const CurveBin& b : bins) ties += !std::isnan(x.value) && (x.rho == b.rho_lo || x.rho == b.rho_hi);
  }
  // The cases meant to be met were met.
  EXPECT_GT(ties, 100u);
  EXPECT_GT(single, 100u);
  EXPECT_GT(several, 1000u);
  EXPECT_GT(infinite, 5u);
}

// A sample on an edge belongs to the bin whose reported bounds hold it, [rho_lo, rho_hi), even
// where rho / width rounds across the edge (0.705 / 0.003 = 234.99999999999997).
TEST(EnsembleCurve, ASampleOnAnEdgeIsInTheBinThatStartsThere) {
  const double at = 235 * 0.003;
  const auto bins = bin_curve(std::vector<CurveSample>{{at, 0, 1, 0}}, {.width = 0.003});
  ASSERT_EQ(bins.size(), 1u);
  EXPECT_EQ(bins[0].rho_lo, at);
  const auto below = bin_curve(std::vector<CurveSample>{{std::nextafter(at, 0.0), 0, 1, 0}}, {.width = 0.003});
  EXPECT_EQ(below[0].rho_hi, at);
}

// The sums run over each run's samples in the order given, then over the runs by index: the
// bins do not depend on how the runs' samples are interleaved.
TEST(EnsembleCurve, InterleavingTheRunsChangesNoBit) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> rho(0.63, 0.90), value(0, 1);
  std::vector<std::vector<CurveSample>> runs(5);
  for (std::size_t r = 0; r < runs.size(); ++r)
    for (int f = 0; f < 80; ++f) runs[r].push_back({rho(rng), value(rng), value(rng) * 1e3, r});
  std::vector<CurveSample> forward, backward, interleaved;  // backward: the runs last to first
  for (const auto& run : runs) forward.insert(forward.end(), run.begin(), run.end());
  for (auto run = runs.rbegin(); run != runs.rend(); ++run) backward.insert(backward.end(), run->begin(), run->end());
  std::vector<std::size_t> next(runs.size(), 0);
  while (interleaved.size() < forward.size()) {
    const std::size_t r = std::uniform_int_distribution<std::size_t>(0, runs.size() - 1)(rng);
    if (next[r] < runs[r].size()) interleaved.push_back(runs[r][next[r]++]);
  }
  for (const auto& binning : {RhoBinning{.width = 0.01}, RhoBinning{.count = 7}}) {
    const auto a = bin_curve(forward, binning);
    for (const auto& other : {backward, interleaved}) {
      const auto b = bin_curve(other, binning);
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].mean, b[k].mean);
        EXPECT_EQ(a[k].standard_error, b[k].standard_error);
        EXPECT_EQ(a[k].mean_rho, b[k].mean_rho);
        EXPECT_EQ(a[k].mean_z, b[k].mean_z);
      }
    }
  }
}

TEST(EnsembleCurve, RatioOfTheBinMeans) {
  const std::vector<CurveSample> db{{0.701, 1, 1, 0}, {0.705, 1, 3, 1}, {0.751, 1, 0, 0}};
  const std::vector<CurveSample> w2{
      {0.701, 1, 4, 0}, {0.705, 1, 4, 1}, {0.706, 1, 4, 1}, {0.751, 1, 0, 0}, {0.801, 1, 1, 0}};
  const auto ratio = ratio_curve(bin_curve(db, {.width = 0.05}), bin_curve(w2, {.width = 0.05}));
  ASSERT_EQ(ratio.size(), 2u);           // the 0.80 bin has no numerator
  EXPECT_DOUBLE_EQ(ratio[0].mean, 0.5);  // mean 2 over mean 4, not the mean of the ratios 1/4, 3/4
  EXPECT_EQ(ratio[0].n, 2u);             // the smaller of 2 and 3
  EXPECT_EQ(ratio[0].runs, 2u);
  EXPECT_EQ(ratio[1].runs, 1u);
  EXPECT_FALSE(ratio[0].standard_error.has_value());
  EXPECT_TRUE(std::isnan(ratio[1].mean));  // 0 / 0
}

}  // namespace
}  // namespace fnet
