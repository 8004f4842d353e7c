// fnetctl watch: the loop. It waits for the run, subscribes, reconnects, polls the run's summary
// for completion and the plan, and hands the state to the renderer (watch_view.hpp).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <iostream>
#include <optional>
#include <sstream>
#include <thread>

#include "client/fnetctl/cli_options.hpp"
#include "client/fnetctl/commands.hpp"
#include "client/fnetctl/terminal_screen.hpp"
#include "client/fnetctl/value_text.hpp"
#include "client/fnetctl/watch_view.hpp"
#include "client/rpc/rpc_client.hpp"
#include "proto/json_rpc.hpp"

namespace fnet::client {

namespace po = boost::program_options;
using namespace std::chrono_literals;

namespace {

std::atomic<bool> interrupted{false};

void on_signal(int) { interrupted = true; }

// Sleeps up to `total`, waking early on Ctrl-C.
void pause(std::chrono::milliseconds total) {
  for (auto slept = 0ms; slept < total && !interrupted; slept += 100ms) std::this_thread::sleep_for(100ms);
}

// The plan and completion from the run's summary (run.get). A run whose last frames were rejected
// or skipped never sends its last planned frame: it is complete once every planned frame is
// accounted for and the last analyzed one has been shown.
void update_from_summary(WatchState& state, const json& summary) {
  state.run = summary.at("run").get<std::string>();
  if (summary.contains("planned_frames")) state.planned_frames = summary["planned_frames"].get<std::uint32_t>();
  if (summary.contains("rho_j") && summary["rho_j"].is_number()) state.rho_j = summary["rho_j"].get<double>();
  const json& parameters = summary.value("parameters", json());
  if (parameters.is_object() && parameters.contains("final_density"))
    state.rho_end = parameters["final_density"].get<double>();
  if (parameters.is_object() && parameters.contains("friction"))
    state.setting = "mu " + rounded_number(parameters["friction"].get<double>(), 6) + ", N " +
                    std::to_string(parameters.value("particles", 0u)) + ", v_c " +
                    rounded_number(parameters.value("compression_speed", 0.0), 6) +
                    " d/tau_c; distances in units of the mean force, floor convention";
  if (!state.planned_frames) return;
  const auto count = [&](const char* key) { return summary.value(key, std::size_t{0}); };
  const bool accounted =
      count("frames") + count("rejected") + count("skipped") >= *state.planned_frames && count("pending") == 0;
  const json& last = summary.value("last_frame", json());
  const bool shown = last.is_null() || (state.last && state.last->frame >= last.get<std::uint32_t>());
  if (accounted && shown) state.complete = true;
}

struct WatchOptions {
  std::string run;
  std::string trend_key;
  std::vector<std::string> keys;
  double wait_seconds = 60;
  bool plain = false, until_complete = false;
};

// --series: "all" or a comma-separated list of series keys, each checked.
std::vector<std::string> series_option(const std::string& text) {
  const std::vector<std::string> all = all_series_keys();
  if (text == "all") return all;
  std::vector<std::string> keys;
  std::stringstream in(text);
  for (std::string key; std::getline(in, key, ',');) {
    if (std::find(all.begin(), all.end(), key) == all.end())
      throw po::error("--series: '" + key + "' is not a stored series; they are metric/pdD/force, e.g. " + all[2] +
                      ", or all");
    keys.push_back(key);
  }
  if (keys.empty()) throw po::error("--series: name at least one series, or all");
  return keys;
}

double seconds_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The runs the server has, for the message of a run that never appeared.
std::string known_runs(RpcClient& rpc) {
  const json runs = rpc.call("runs.list").at("runs");
  if (runs.empty()) return "the server has no runs";
  std::string out = "the server has";
  for (std::size_t k = 0; k < runs.size() && k < 20; ++k) out += (k ? ", " : " ") + runs[k]["run"].get<std::string>();
  if (runs.size() > 20) out += " and " + std::to_string(runs.size() - 20) + " more";
  return out;
}

std::optional<WatchOptions> parse_watch(const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl watch [--run R] [--series all|KEYS] [--metric M] [--dim D] [--force F] [--plain]\n"
      "                     [--until-complete] [--wait S]\n\n"
      "Follows a run live: frames as fnet-simd counts them with the time left at the rate they arrive\n"
      "(ETA), the server's lag, rho, Z and rho_J, and per series its latest distance and a sparkline\n"
      "of the last 60 frames on a log scale (a dot: 0) with its min and max, rho_J marked under them.\n"
      "Waits for the run to appear (the newest run when --run is not given; a named run that has not\n"
      "appeared after --wait seconds is an error listing the server's runs, exit 4), reconnects by\n"
      "itself and resumes after the last frame it showed, and marks the run complete when its last\n"
      "planned frame has been analyzed. Draws on the terminal's alternate screen, given back on exit.\n"
      "--plain prints one line per frame with the series of --metric, --dim, --force. Ctrl-C leaves.\n\n"
      "options");
  WatchOptions w;
  std::string metric = "wasserstein2", force = "normal", series = "all";
  long long dim = kDefaultDim;
  o.add_options()("help,h", "show this help")("run", po::value(&w.run), "run id (default: the newest run)")(
      "metric", po::value(&metric)->default_value("wasserstein2"),
      "series of the trend line: bottleneck, wasserstein1 or wasserstein2")(
      "dim", po::value(&dim)->default_value(kDefaultDim), "homology dimension of the trend: 0 or 1")(
      "force", po::value(&force)->default_value("normal"), "force network of the trend: normal or tangential")(
      "plain", po::bool_switch(&w.plain), "one line per frame instead of a screen redrawn in place")(
      "until-complete", po::bool_switch(&w.until_complete), "exit when the run is complete")(
      "series", po::value(&series)->default_value("all"),
      "the sparklines: all twelve, or keys metric/pdD/force separated by commas")(
      "wait", po::value(&w.wait_seconds)->default_value(60), "seconds to wait for a run named by --run to appear");
  if (!parse_command(o, args)) return std::nullopt;
  std::optional<Metric> stored;
  for (const Metric m : kMetrics)
    if (metric == to_string(m)) stored = m;
  if (!stored)
    throw po::error(
        "--metric: watch follows a series computed as frames arrive: bottleneck, wasserstein1 or "
        "wasserstein2, got '" +
        metric + "'");
  w.trend_key = series_key(*stored, dim_option(dim), force_option(force));
  w.keys = series_option(series);
  if (!(w.wait_seconds > 0) || !std::isfinite(w.wait_seconds))
    throw po::error("--wait must be a positive number of seconds");
  return w;
}

}  // namespace

int watch_command(const Endpoint& at, const std::vector<std::string>& args) {
  const std::optional<WatchOptions> options = parse_watch(args);
  if (!options) return kOk;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  WatchState state;
  state.run = options->run;
  state.trend_key = options->trend_key;
  state.keys = options->keys;
  const double waiting_since = seconds_now();
  std::optional<AlternateScreen> screen;
  if (!options->plain) screen.emplace(std::cout);
  std::string printed_status;
  bool printed_complete = false;
  std::optional<std::uint32_t> printed_frame;
  const auto show = [&] {
    if (screen) return screen->draw(render_watch_screen(state));
    if (!state.status.empty() && state.status != printed_status) std::cout << state.status << std::endl;
    printed_status = state.status;
    if (state.last && state.last->frame != printed_frame) std::cout << render_watch_line(state) << std::endl;
    if (state.last) printed_frame = state.last->frame;
    if (state.complete && !printed_complete) std::cout << "run " << state.run << " complete" << std::endl;
    printed_complete = state.complete;
  };

  int failures = 0;
  while (!interrupted) {
    try {
      RpcClient rpc(at.host, at.port, 10s, at.token, at.tls);
      json summary;
      while (!interrupted) {  // the run may not exist yet: fnet-simd may still be relaxing
        try {
          summary = rpc.call("run.get", options->run.empty() ? json::object() : json{{"run", options->run}});
          break;
        } catch (const CallError& e) {
          if (e.code() != rpc::kUnknownRun) throw;
          if (!options->run.empty() && seconds_now() - waiting_since > options->wait_seconds) {
            screen.reset();
            std::cerr << "fnetctl watch: run " << options->run << " has not appeared after "
                      << rounded_number(options->wait_seconds, 6) << " s; " << known_runs(rpc) << "\n";
            return kUnknown;
          }
          state.status = options->run.empty() ? "waiting for a run to appear on the server..."
                                              : "waiting for run " + options->run + " to appear on the server...";
          show();
          pause(500ms);
        }
      }
      if (interrupted) break;
      update_from_summary(state, summary);
      json subscribe = {{"run", state.run}};
      if (state.last) subscribe["since"] = state.last->frame;
      rpc.call("series.subscribe", subscribe);
      failures = 0;
      state.status = state.last ? "" : "waiting for the first analyzed frame...";
      show();
      auto polled = std::chrono::steady_clock::now();
      while (!interrupted && !(options->until_complete && state.complete)) {
        if (const std::optional<json> n = rpc.next_notification(200ms)) {
          state.add(watch_point_from_json(n->at("params")), seconds_now());
          state.status.clear();
          show();
        }
        // Every 2 s, also while frames keep arriving: rho_J, the plan and the lag change with them.
        if (!state.complete && std::chrono::steady_clock::now() - polled > 2s) {
          update_from_summary(state, rpc.call("run.get", {{"run", state.run}}));
          const json lag = rpc.call("server.status").at("lag");
          state.server_in_flight = lag.at("frames_in_flight").get<std::size_t>();
          state.server_oldest_pending = lag.at("oldest_pending_seconds").get<double>();
          polled = std::chrono::steady_clock::now();
          show();
        }
      }
      if (state.complete) break;  // --until-complete
    } catch (const ConnectionError& e) {
      if (++failures > 30) throw;
      state.status = std::string(e.what()) + "; reconnecting...";
      show();
      pause(1s);
    }
  }
  // The alternate screen goes with its contents: the last frame stays on the screen as one line.
  if (screen) {
    screen.reset();
    if (state.last) std::cout << render_watch_line(state) << std::endl;
  }
  return kOk;
}

}  // namespace fnet::client
