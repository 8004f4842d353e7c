// The watch screen as a pure function of what watch knows: frames counted as fnet-simd counts
// them, a complete run marked, every series as a log-scaled sparkline with its scale, rho_J marked,
// the ETA from the frames' arrivals, and the waiting states.
#include "client/fnetctl/watch_view.hpp"

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
  s.keys = all_series_keys();
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

TEST(WatchView, EverySeriesIsALogSparklineWithItsScale) {
  WatchState s = state_with(100);
  s.add(point(0, 0.63, std::nullopt));
  s.add(point(1, 0.64, 0.002));
  s.add(point(2, 0.65, 0.5));
  s.add(point(3, 0.66, 0.125));
  const std::string screen = render_watch_screen(s);
  EXPECT_THAT(screen, AllOf(HasSubstr("wasserstein2 PD0 normal"), HasSubstr("min 0.002 / max 0.5"),
                            HasSubstr("last 4 frames, log scale"), HasSubstr("bottleneck PD1 tangential")));
  // The row of the series: its latest value, then one bar per frame (none for the first frame).
  EXPECT_THAT(screen, HasSubstr("0.125   \u2581\u2588\u2586"));
  // Log scale: 0.002, 0.5, 0.125 are 10^-2.70, 10^-0.30, 10^-0.90: bars 0, 7 and 5 of 0..7.
  EXPECT_EQ(log_sparkline({0.002, 0.5, 0.125}), "\u2581\u2588\u2586");
  // A zero cannot sit on a log scale: a dot; a frame without the value: a space.
  EXPECT_EQ(log_sparkline({1.0, 0.0, std::nullopt, 100.0}), "\u2581\u00b7 \u2588");
  EXPECT_EQ(log_sparkline({}), "");
  EXPECT_EQ(log_sparkline({1.0, 1.0}), "\u2581\u2581");
  WatchState chosen = state_with(100);
  chosen.keys = {kKey};
  chosen.add(point(0, 0.63, std::nullopt));
  EXPECT_THAT(render_watch_screen(chosen), Not(HasSubstr("bottleneck PD1 tangential")));
}

TEST(WatchView, TheHistoryKeepsTheLatestFramesOnly) {
  WatchState s = state_with(std::nullopt);
  for (std::uint32_t k = 0; k <= kTrendLength + 10; ++k)
    s.add(point(k, 0.7, k ? std::optional(double(k)) : std::nullopt));
  ASSERT_EQ(s.history.size(), kTrendLength);
  EXPECT_EQ(s.history.back().frame, kTrendLength + 10);
  EXPECT_EQ(s.history.front().frame, 11u);
}

TEST(WatchView, RhoJIsMarkedUnderTheSparklines) {
  WatchState s = state_with(100);
  EXPECT_THAT(render_watch_screen(s), Not(HasSubstr("rho_J")));  // nothing shown before a frame
  s.add(point(0, 0.63, std::nullopt));
  EXPECT_THAT(render_watch_screen(s), HasSubstr("rho_J not yet (Z has not reached 3)"));
  for (std::uint32_t k = 1; k < 6; ++k) s.add(point(k, 0.63 + 0.01 * k, 0.1 * k));
  s.rho_j = 0.655;  // first reached by frame 3 (rho 0.66), the fourth column
  const std::string screen = render_watch_screen(s);
  EXPECT_THAT(screen, HasSubstr("rho_J 0.6550 (Z first reached 3)"));
  const auto marker = screen.find("^ rho_J (frame 3)");
  ASSERT_NE(marker, std::string::npos);
  const auto line_start = screen.rfind('\n', marker) + 1;
  EXPECT_EQ(marker - line_start, 26u + 12u + 2u + 3u);  // label, latest value, gap, three columns
  EXPECT_THAT(render_watch_line(s), HasSubstr("past rho_J"));
}

TEST(WatchView, TheEtaFollowsTheRateFramesArrive) {
  WatchState s = state_with(100);
  for (std::uint32_t k = 0; k < 4; ++k) s.add(point(k, 0.63, k ? std::optional(0.5) : std::nullopt), 10.0 + 2.0 * k);
  ASSERT_TRUE(s.eta_seconds());
  EXPECT_DOUBLE_EQ(*s.eta_seconds(), 96 * 2.0);  // 96 frames left, one every 2 s
  EXPECT_THAT(render_watch_screen(s), HasSubstr("ETA 3m12s"));
  WatchState burst = state_with(100);  // frames replayed at once after a reconnection
  for (std::uint32_t k = 0; k < 4; ++k) burst.add(point(k, 0.63, std::nullopt), 5.0 + 1e-4 * k);
  EXPECT_FALSE(burst.eta_seconds());
  EXPECT_EQ(duration_text(3725), "1h02m");
  EXPECT_EQ(duration_text(37), "37s");
  s.server_in_flight = 2;
  s.server_oldest_pending = 0.5;
  EXPECT_THAT(render_watch_screen(s), HasSubstr("server lag 2 frames (0.50 s)"));
  s.setting = "mu 0.5, N 2000";
  EXPECT_THAT(render_watch_screen(s), HasSubstr("mu 0.5, N 2000"));
}

TEST(WatchView, DistancesShowEverySeriesAndDashesWithoutAPreviousFrame) {
  WatchState s = state_with(10);
  s.add(point(0, 0.63, std::nullopt));
  EXPECT_THAT(render_watch_screen(s), AllOf(HasSubstr("bottleneck PD0 normal"), HasSubstr("wasserstein1 PD1 normal"),
                                            HasSubstr("wasserstein2 PD1 tangential"), HasSubstr(" -")));
  s.add(point(1, 0.64, 0.75));
  EXPECT_THAT(render_watch_screen(s), AllOf(HasSubstr("distance from frame 0"), HasSubstr("0.75"), HasSubstr("0.25")));
}

TEST(WatchView, WaitingStatesSayWhatIsAwaited) {
  WatchState s = state_with(std::nullopt);
  s.status = "waiting for run demo to appear";
  EXPECT_THAT(render_watch_screen(s), AllOf(HasSubstr("run demo"), HasSubstr("waiting for run demo to appear")));
  WatchState newest;
  newest.trend_key = kKey;
  newest.keys = all_series_keys();
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
