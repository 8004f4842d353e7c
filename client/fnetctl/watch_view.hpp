// What `fnetctl watch` shows, as pure functions of what it knows. The loop that gathers the state
// (connection, subscription, reconnection, signals, the terminal) lives in watch_command.cpp; the
// screen is drawn from a WatchState alone, so it is tested without a server or a terminal.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fnet::client {

// One analyzed frame, as a series.point notification carries it (proto/api.md).
struct WatchPoint {
  std::uint32_t frame = 0;
  std::uint64_t step = 0;
  double time = 0, rho = 0, z = 0;  // time in tau_c since the compression began
  std::optional<std::uint32_t> previous;
  std::map<std::string, double> distances;  // series key -> value; empty without a previous frame
};

// Throws nlohmann::json::exception when a field is missing or of the wrong type.
WatchPoint watch_point_from_json(const nlohmann::json& params);

// The twelve stored series, "metric/pdD/force", in the order the screen lists them.
std::vector<std::string> all_series_keys();

inline constexpr std::size_t kTrendLength = 60;
// Frames whose arrival times estimate the time to the run's end.
inline constexpr std::size_t kRateWindow = 10;

struct WatchState {
  std::string run;                // empty while watch waits for the server's newest run
  std::string trend_key;          // the series of the one-line view, "metric/pdD/force"
  std::vector<std::string> keys;  // the series drawn as sparklines (default: all twelve)
  std::string setting;            // "mu 0.5, N 2000, v_c 2.5e-05 d/tau_c", once announced
  std::optional<std::uint32_t> planned_frames;
  std::optional<double> rho_start;  // of the first frame seen
  std::optional<double> rho_end;    // the run's final density, once announced
  std::optional<double> rho_j;      // where Z first reached 3 (run.get), once it has
  std::optional<WatchPoint> last;
  std::deque<WatchPoint> history;               // the latest kTrendLength frames, oldest first
  std::deque<double> arrivals;                  // seconds (any fixed origin) when the latest frames arrived
  std::optional<std::size_t> server_in_flight;  // server.status lag: frames received, not committed
  std::optional<double> server_oldest_pending;  // seconds the oldest of them has waited
  bool complete = false;                        // every planned frame has been analyzed (or rejected)
  std::string status;                           // what watch waits for, or why it reconnects; empty while live

  // A new frame that arrived at `arrived` seconds: the latest point, the history, completion when
  // it is the last planned frame.
  void add(const WatchPoint& point, double arrived = 0);
  // Seconds until the last planned frame at the rate the latest frames arrived (the median gap
  // between their arrivals); none before two gaps are known, without a plan, once complete, or
  // while the frames arrive faster than a simulation publishes them (stored frames replayed).
  std::optional<double> eta_seconds() const;
};

// "frames 12/100" once frame 11 of 100 planned has arrived: fnet-simd's count (frames are
// numbered from 0). "frames 12" while the plan is unknown.
std::string frame_count(const WatchState& state);

// The whole screen, lines separated by '\n'.
std::string render_watch_screen(const WatchState& state);

// One line for the latest frame (--plain).
std::string render_watch_line(const WatchState& state);

// One bar per value on a log scale: the smallest positive value at the lowest bar, the largest at
// the highest; a value <= 0 (which a log scale cannot show) is drawn as a dot, a missing one as a
// space.
std::string log_sparkline(const std::vector<std::optional<double>>& values);

// "4m12s", "1h03m", "37s".
std::string duration_text(double seconds);

}  // namespace fnet::client
