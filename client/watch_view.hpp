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

#include <nlohmann/json.hpp>

namespace fnet::client {

// One analyzed frame, as a series.point notification carries it (proto/api.md).
struct WatchPoint {
  std::uint32_t frame = 0;
  std::uint64_t step = 0;
  double time = 0, rho = 0, z = 0;
  std::optional<std::uint32_t> previous;
  std::map<std::string, double> distances;  // series key -> value; empty without a previous frame
};

// Throws nlohmann::json::exception when a field is missing or of the wrong type.
WatchPoint watch_point_from_json(const nlohmann::json& params);

inline constexpr std::size_t kTrendLength = 60;

struct WatchState {
  std::string run;        // empty while watch waits for the server's newest run
  std::string trend_key;  // the series of the trend line, "metric/pdD/force"
  std::optional<std::uint32_t> planned_frames;
  std::optional<double> rho_start;  // of the first frame seen
  std::optional<double> rho_end;    // the run's final density, once announced
  std::optional<WatchPoint> last;
  std::deque<double> trend;  // the trend series' latest kTrendLength values, oldest first
  bool complete = false;     // every planned frame has been analyzed (or rejected)
  std::string status;        // what watch waits for, or why it reconnects; empty while live

  // A new frame: the latest point, the trend, and completion when it is the last planned frame.
  void add(const WatchPoint& point);
};

// "frames 12/100" once frame 11 of 100 planned has arrived: fnet-simd's count (frames are
// numbered from 0). "frames 12" while the plan is unknown.
std::string frame_count(const WatchState& state);

// The whole screen, lines separated by '\n'.
std::string render_watch_screen(const WatchState& state);

// One line for the latest frame (--plain).
std::string render_watch_line(const WatchState& state);

// One bar per value, the lowest value at the lowest bar and the highest at the highest.
std::string sparkline(const std::deque<double>& values);

}  // namespace fnet::client
