// The watch screen as a pure function of what watch knows: frames counted as fnet-simd counts
// them, a complete run marked, the trend line with its scale, and the waiting states.
#include "client/watch_view.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fnet::client {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

const std::string kKey = "wasserstein2/pd0/normal";

WatchPoint point(std::uint32_t frame, double rho, std::optional<double> trend) {
  WatchPoint p;
  p.frame = frame;
  p.step = 1000 * frame;
  p.time = 2.5 * frame;
  p.rho = rho;
  p.z = 3.5;
  if (trend) {
    p.previous = frame - 1;
    p.distances[kKey] = *trend;
    p.distances["bottleneck/pd1/tangential"] = 0.25;
  }
  return p;
}

WatchState state_with(std::optional<std::uint32_t> planned) {
  WatchState s;
  s.run = "demo";
  s.trend_key = kKey;
  s.planned_frames = planned;
  s.rho_end = 0.9;
  return s;
}

TEST(WatchView, CountsFramesAsFnetSimdDoes) {
  WatchState s = state_with(100);
  for (std::uint32_t k = 0; k < 12; ++k) s.add(point(k, 0.63 + 0.01 * k, k ? std::optional(0.1 * k) : std::nullopt));
  // Frame 11 is the twelfth frame: fnet-simd's "frames 12/100".
  EXPECT_EQ(frame_count(s), "frames 12/100");
  EXPECT_THAT(render_watch_screen(s), AllOf(HasSubstr("frames 12/100"), HasSubstr("frame 11"), HasSubstr("step 11000"),
                                            Not(HasSubstr("complete"))));
  EXPECT_THAT(render_watch_line(s), AllOf(HasSubstr("frame 11"), HasSubstr("12/100")));
  EXPECT_EQ(frame_count(state_with(std::nullopt)), "frames 0");
  WatchState unplanned = state_with(std::nullopt);
  unplanned.add(point(4, 0.7, std::nullopt));
  EXPECT_EQ(frame_count(unplanned), "frames 5");
}

TEST(WatchView, TheLastPlannedFrameMarksTheRunComplete) {
  WatchState s = state_with(3);
  s.add(point(0, 0.63, std::nullopt));
  s.add(point(1, 0.64, 0.5));
  EXPECT_FALSE(s.complete);
  s.add(point(2, 0.65, 0.25));
  EXPECT_TRUE(s.complete);
  EXPECT_THAT(render_watch_screen(s), AllOf(HasSubstr("complete"), HasSubstr("frames 3/3")));
  EXPECT_THAT(render_watch_line(s), HasSubstr("complete"));
}

TEST(WatchView, TheTrendLineCarriesItsScale) {
  WatchState s = state_with(100);
  s.add(point(0, 0.63, std::nullopt));
  s.add(point(1, 0.64, 0.002));
  s.add(point(2, 0.65, 0.5));
  s.add(point(3, 0.66, 0.125));
  const std::string screen = render_watch_screen(s);
  EXPECT_THAT(screen, AllOf(HasSubstr(kKey), HasSubstr("min 0.002"), HasSubstr("max 0.5"), HasSubstr("last 3 frames")));
  // Lowest and highest bars at the ends of the scale.
  EXPECT_EQ(sparkline({0.002, 0.5, 0.125}), "\u2581\u2588\u2583");
  EXPECT_EQ(sparkline({}), "");
  EXPECT_EQ(sparkline({1, 1}), "\u2581\u2581");
}

TEST(WatchView, TheTrendKeepsTheLatestValuesOnly) {
  WatchState s = state_with(std::nullopt);
  for (std::uint32_t k = 0; k <= kTrendLength + 10; ++k)
    s.add(point(k, 0.7, k ? std::optional(double(k)) : std::nullopt));
  ASSERT_EQ(s.trend.size(), kTrendLength);
  EXPECT_EQ(s.trend.back(), double(kTrendLength + 10));
  EXPECT_EQ(s.trend.front(), 11.0);
}

TEST(WatchView, DistancesTableShowsEverySeriesAndDashesWithoutAPreviousFrame) {
  WatchState s = state_with(10);
  s.add(point(0, 0.63, std::nullopt));
  EXPECT_THAT(render_watch_screen(s), AllOf(HasSubstr("bottleneck"), HasSubstr("wasserstein1"),
                                            HasSubstr("wasserstein2"), HasSubstr("tangential PD1"), HasSubstr(" -")));
  s.add(point(1, 0.64, 0.75));
  EXPECT_THAT(render_watch_screen(s), AllOf(HasSubstr("distance from frame 0"), HasSubstr("0.75"), HasSubstr("0.25")));
}

TEST(WatchView, WaitingStatesSayWhatIsAwaited) {
  WatchState s = state_with(std::nullopt);
  s.status = "waiting for run demo to appear";
  EXPECT_THAT(render_watch_screen(s), AllOf(HasSubstr("run demo"), HasSubstr("waiting for run demo to appear")));
  WatchState newest;
  newest.trend_key = kKey;
  newest.status = "waiting for a run";
  EXPECT_THAT(render_watch_screen(newest), HasSubstr("waiting for a run"));
}

TEST(WatchView, TheDensityBarRunsFromTheFirstFrameToTheFinalDensity) {
  WatchState s = state_with(10);
  s.add(point(0, 0.6, std::nullopt));
  s.add(point(1, 0.75, 0.1));  // half way from 0.6 to 0.9
  const std::string screen = render_watch_screen(s);
  EXPECT_THAT(screen, AllOf(HasSubstr("rho 0.7500 [" + std::string(20, '#') + std::string(20, '.') + "] 0.9000")));
}

}  // namespace
}  // namespace fnet::client
