#include "common/analysis/step_series.hpp"

#include <gtest/gtest.h>

namespace fnet {
namespace {

// A frame whose normal PD1 is `pd1` and whose stored distances all read `stored`.
std::shared_ptr<const AnalyzedFrame> frame(std::uint32_t index, Diagram pd1, std::optional<std::uint32_t> previous,
                                           double stored) {
  auto f = std::make_shared<AnalyzedFrame>();
  f->header.index = index;
  f->header.rho = 0.7 + 0.01 * index;
  f->header.z = 2.0 + index;
  f->diagrams.normal.pd1 = std::move(pd1);
  f->previous = previous;
  f->distances.value.fill(stored);
  return f;
}

StepQuery query(const MetricChoice& metric, EssentialConvention essential = EssentialConvention::floor) {
  return {metric, 1, ForceKind::normal, essential};
}

// (2, 1) and (3, 1): matched to each other at L-infinity cost 1, against 0.5 and 1 to the diagonal.
const std::vector<std::shared_ptr<const AnalyzedFrame>> kFrames{
    frame(0, {{2, 1}}, std::nullopt, 0), frame(1, {{3, 1}}, 0, 42), frame(3, {{3, 1}}, std::nullopt, 7),
    frame(4, {{2, 1}}, 3, 42)};

TEST(StepSeries, StoredSeriesAreServedAsStored) {
  std::vector<StepValue> steps;
  append_step_values(kFrames, query(parse_metric("bottleneck")), 0, steps);
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_FALSE(steps[0].value) << "the first frame has no previous frame";
  EXPECT_EQ(steps[1].value, 42.0);
  EXPECT_FALSE(steps[2].value) << "a frame without a previous accepted frame";
  EXPECT_EQ(steps[3].value, 42.0);
  EXPECT_EQ(steps[3].index, 4u);
  EXPECT_EQ(steps[3].rho, kFrames[3]->header.rho);
  EXPECT_EQ(steps[3].z, 6.0);
}

TEST(StepSeries, OtherMetricsAndConventionsAreComputedFromTheDiagrams) {
  for (const StepQuery& q :
       {query(parse_metric("wasserstein", 3)), query(parse_metric("bottleneck"), EssentialConvention::sentinel)}) {
    std::vector<StepValue> steps;
    append_step_values(kFrames, q, 0, steps);
    ASSERT_EQ(steps.size(), 4u);
    EXPECT_DOUBLE_EQ(*steps[1].value, 1.0);
    EXPECT_DOUBLE_EQ(*steps[3].value, 1.0);
  }
}

TEST(StepSeries, AppendingTheNewFramesEqualsComputingThemAll) {
  const StepQuery q = query(parse_metric("wasserstein", 3));
  std::vector<StepValue> all, some;
  append_step_values(kFrames, q, 0, all);
  append_step_values(std::span(kFrames).first(2), q, 0, some);
  append_step_values(kFrames, q, 2, some);
  ASSERT_EQ(some.size(), all.size());
  for (std::size_t k = 0; k < all.size(); ++k) {
    EXPECT_EQ(some[k].index, all[k].index);
    EXPECT_EQ(some[k].value, all[k].value);
  }
}

TEST(StepSeries, CurveSamplesAreTheFramesWithAValueShifted) {
  std::vector<StepValue> steps;
  append_step_values(kFrames, query(parse_metric("bottleneck")), 0, steps);
  const auto samples = curve_samples(steps, 0.5, 7);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[0].run, 7u);
  EXPECT_EQ(samples[1].run, 7u);
  EXPECT_EQ(samples[0].rho, kFrames[1]->header.rho - 0.5);
  EXPECT_EQ(samples[1].z, 6.0);
  EXPECT_EQ(samples[1].value, 42.0);
}

}  // namespace
}  // namespace fnet
