// fnetctl: the command-line client of fnet-server.
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <deque>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include <boost/program_options.hpp>

#include "client/rpc_client.hpp"
#include "proto/json_rpc.hpp"

namespace po = boost::program_options;
using fnet::client::json;

namespace {

// Exit codes, documented in --help and README.
enum Exit : int { kOk = 0, kFailure = 1, kUsage = 2, kUnreachable = 3, kUnknown = 4, kServerError = 5 };

constexpr const char* kUsageText =
    "usage: fnetctl [--host H] [--port P] <command> [options]\n"
    "\n"
    "commands:\n"
    "  runs       the runs the server knows, newest activity last\n"
    "  query      a distance time series: --metric bottleneck|wasserstein1|wasserstein2|wasserstein [--q Q]\n"
    "             [--run R] [--dim 0|1] [--force normal|tangential] [--essential floor|sentinel|separate]\n"
    "             [--from F] [--to T] [--format table|csv|json]\n"
    "  watch      live view of a compression (rho, Z, latest distances, trend); Ctrl-C to leave\n"
    "  diagram    a frame's persistence diagram: --frame K [--run R] [--dim] [--force] [--format]\n"
    "  distance   distance between two frames, also across runs: --frame A --other-frame B\n"
    "             [--run R] [--other-run R2] --metric M [--q Q] [--dim] [--force] [--delta D]\n"
    "  status     server health: uptime, frames/s, lag, rejected frames with reasons\n"
    "\n"
    "global options: --host (default 127.0.0.1), --port (default 7707)\n"
    "exit codes: 0 ok, 2 bad usage or parameter, 3 server unreachable, 4 unknown run or frame,\n"
    "            5 other server error, 1 anything else\n"
    "Run 'fnetctl <command> --help' for a command's options.\n";

std::atomic<bool> interrupted{false};

// Connects on first use, so --help and bad options never need a server.
class Connection {
 public:
  Connection(std::string host, unsigned short port) : host_(std::move(host)), port_(port) {}
  fnet::client::RpcClient& operator()() {
    if (!client_) client_ = std::make_unique<fnet::client::RpcClient>(host_, port_);
    return *client_;
  }

 private:
  std::string host_;
  unsigned short port_;
  std::unique_ptr<fnet::client::RpcClient> client_;
};

std::string number(const json& v, int precision = 6) {
  if (v.is_null()) return "-";
  std::ostringstream s;
  s << std::setprecision(precision) << v.get<double>();
  return s.str();
}

struct Common {
  std::string run, force = "normal", essential = "floor", format = "table", metric;
  int dim = 0;
  double q = 0;

  void add(po::options_description& o, bool with_metric) {
    o.add_options()("help,h", "show this help")("run", po::value(&run), "run id (default: the newest run)")(
        "dim", po::value(&dim)->default_value(0), "homology dimension: 0 (components) or 1 (loops)")(
        "force", po::value(&force)->default_value("normal"), "normal or tangential force network");
    if (with_metric)
      o.add_options()("metric", po::value(&metric)->required(),
                      "bottleneck, wasserstein1, wasserstein2 or wasserstein")(
          "q", po::value(&q), "exponent q >= 1 for --metric wasserstein")(
          "essential", po::value(&essential)->default_value("floor"),
          "never-dying classes: floor, sentinel or separate");
  }
  json params() const {
    json p = {{"dim", dim}, {"force", force}};
    if (!run.empty()) p["run"] = run;
    if (!metric.empty()) {
      p["metric"] = metric;
      p["essential"] = essential;
      if (q > 0) p["q"] = q;
    }
    return p;
  }
};

bool parse(po::options_description& o, const std::vector<std::string>& args,
           po::positional_options_description* pos = nullptr) {
  po::variables_map vm;
  auto parser = po::command_line_parser(args).options(o);
  if (pos) parser.positional(*pos);
  po::store(parser.run(), vm);
  if (vm.count("help")) {
    std::cout << o << "\n";
    return false;
  }
  po::notify(vm);
  return true;
}

void check_format(const std::string& format, std::initializer_list<const char*> allowed) {
  for (const char* a : allowed)
    if (format == a) return;
  throw po::error("unknown --format '" + format + "'");
}

int cmd_runs(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o("usage: fnetctl runs [--format table|json]\n\noptions");
  std::string format = "table";
  o.add_options()("help,h", "show this help")("format", po::value(&format)->default_value("table"), "table or json");
  if (!parse(o, args)) return kOk;
  check_format(format, {"table", "json"});
  const json r = rpc().call("runs.list");
  if (format == "json") {
    std::cout << r.dump(2) << "\n";
    return kOk;
  }
  std::printf("%-24s %7s %8s %8s %9s %7s %9s\n", "run", "frames", "rejected", "pending", "rho", "Z", "idle(s)");
  for (const json& run : r["runs"])
    std::printf("%-24s %7zu %8zu %8zu %9s %7s %9.1f\n", run["run"].get<std::string>().c_str(),
                run["frames"].get<std::size_t>(), run["rejected"].get<std::size_t>(), run["pending"].get<std::size_t>(),
                number(run["rho"], 5).c_str(), number(run["z"], 4).c_str(),
                run["seconds_since_last_frame"].get<double>());
  return kOk;
}

int cmd_query(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o("usage: fnetctl query --metric M [options]\n\noptions");
  Common c;
  c.add(o, true);
  int from = -1, to = -1;
  o.add_options()("from", po::value(&from), "first frame")("to", po::value(&to), "last frame")(
      "format", po::value(&c.format)->default_value("table"), "table, csv or json");
  if (!parse(o, args)) return kOk;
  check_format(c.format, {"table", "csv", "json"});
  json p = c.params();
  if (from >= 0) p["from"] = from;
  if (to >= 0) p["to"] = to;
  const json r = rpc().call("series.get", p);
  if (c.format == "json") {
    std::cout << r.dump() << "\n";
    return kOk;
  }
  const bool csv = c.format == "csv";
  if (csv)
    std::cout << "frame,rho,z,value\n";
  else
    std::cout << "run " << r["run"].get<std::string>() << ", " << r["metric"].get<std::string>()
              << (r.contains("q") && r["metric"] == "wasserstein" ? " q=" + number(r["q"]) : "") << ", PD"
              << r["dim"].get<int>() << ", " << r["force"].get<std::string>()
              << " forces, essential=" << r["essential"].get<std::string>()
              << "; value[k] = distance from the previous frame\n"
              << std::setw(7) << "frame" << std::setw(11) << "rho" << std::setw(9) << "Z" << std::setw(14) << "value"
              << "\n";
  for (std::size_t k = 0; k < r["frame"].size(); ++k) {
    const std::string value = r["value"][k].is_null() ? (csv ? "" : "-") : number(r["value"][k], 8);
    if (csv)
      std::cout << r["frame"][k] << "," << number(r["rho"][k], 8) << "," << number(r["z"][k], 6) << "," << value
                << "\n";
    else
      std::cout << std::setw(7) << r["frame"][k].get<std::uint32_t>() << std::setw(11) << number(r["rho"][k], 6)
                << std::setw(9) << number(r["z"][k], 4) << std::setw(14) << value << "\n";
  }
  return kOk;
}

int cmd_diagram(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o("usage: fnetctl diagram --frame K [options]\n\noptions");
  Common c;
  c.add(o, false);
  std::uint32_t frame = 0;
  o.add_options()("frame", po::value(&frame)->required(), "frame index")(
      "format", po::value(&c.format)->default_value("table"), "table, csv or json");
  if (!parse(o, args)) return kOk;
  check_format(c.format, {"table", "csv", "json"});
  json p = c.params();
  p["frame"] = frame;
  const json r = rpc().call("diagram.get", p);
  if (c.format == "json") {
    std::cout << r.dump() << "\n";
    return kOk;
  }
  if (c.format == "table")
    std::cout << "run " << r["run"].get<std::string>() << " frame " << frame << " (rho " << number(r["rho"]) << "), PD"
              << c.dim << " of the " << c.force << " force network: " << r["points"].size()
              << " points (death -1: never dies)\n";
  std::cout << (c.format == "csv" ? "birth,death\n" : "");
  for (const json& pt : r["points"])
    std::cout << number(pt[0], 10) << (c.format == "csv" ? "," : "\t") << number(pt[1], 10) << "\n";
  return kOk;
}

int cmd_distance(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o("usage: fnetctl distance --frame A --other-frame B --metric M [options]\n\noptions");
  Common c;
  c.add(o, true);
  std::uint32_t frame = 0, other = 0;
  std::string other_run;
  double delta = 0;
  o.add_options()("frame", po::value(&frame)->required(), "first frame")(
      "other-frame", po::value(&other)->required(), "second frame")("other-run", po::value(&other_run),
                                                                    "run of the second frame (default: the first's)")(
      "delta", po::value(&delta)->default_value(0), "0: exact; > 0: certified relative accuracy");
  if (!parse(o, args)) return kOk;
  json p = c.params();
  p["frame"] = frame;
  p["other_frame"] = other;
  if (!other_run.empty()) p["other_run"] = other_run;
  if (delta > 0) p["delta"] = delta;
  std::cout << rpc().call("distance.get", p).dump() << "\n";
  return kOk;
}

int cmd_status(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o("usage: fnetctl status [--format table|json]\n\noptions");
  std::string format = "table";
  o.add_options()("help,h", "show this help")("format", po::value(&format)->default_value("table"), "table or json");
  if (!parse(o, args)) return kOk;
  check_format(format, {"table", "json"});
  const json s = rpc().call("server.status");
  if (format == "json") {
    std::cout << s.dump(2) << "\n";
    return kOk;
  }
  const json& f = s["frames"];
  std::printf("uptime %.0f s, %zu run(s), %zu connection(s), %zu subscription(s)\n", s["uptime_seconds"].get<double>(),
              s["runs"].size(), s["connections"].get<std::size_t>(), s["subscriptions"].get<std::size_t>());
  std::printf(
      "frames: %zu received, %zu analyzed, %zu rejected, %zu duplicates, %zu late, %zu skipped, %zu malformed\n",
      f["received"].get<std::size_t>(), f["analyzed"].get<std::size_t>(), f["rejected"].get<std::size_t>(),
      f["duplicates"].get<std::size_t>(), f["late"].get<std::size_t>(), f["skipped"].get<std::size_t>(),
      f["malformed"].get<std::size_t>());
  std::printf("rate %.1f frames/s; lag: %zu frame(s) in flight, oldest waiting %.2f s\n",
              s["frames_per_second"].get<double>(), s["lag"]["frames_in_flight"].get<std::size_t>(),
              s["lag"]["oldest_pending_seconds"].get<double>());
  for (const json& reason : s["rejections"]) std::cout << "  rejected: " << reason.get<std::string>() << "\n";
  return kOk;
}

std::string sparkline(const std::deque<double>& values) {
  static const char* kBars[] = {"\u2581", "\u2582", "\u2583", "\u2584", "\u2585", "\u2586", "\u2587", "\u2588"};
  if (values.empty()) return "";
  double lo = values.front(), hi = values.front();
  for (double v : values) lo = std::min(lo, v), hi = std::max(hi, v);
  std::string out;
  for (double v : values) {
    const int k = hi > lo ? static_cast<int>(std::lround(7.0 * (v - lo) / (hi - lo))) : 0;
    out += kBars[std::clamp(k, 0, 7)];
  }
  return out;
}

int cmd_watch(const std::string& host, unsigned short port, const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl watch [--run R] [--metric M] [--dim D] [--force F] [--plain] [--until-complete]\n\n"
      "Follows a run live: frame, rho, Z, the latest distances and a trend line of the chosen series.\n"
      "Reconnects by itself and resumes after the last frame it showed. Ctrl-C leaves.\n\noptions");
  Common c;
  c.add(o, false);
  std::string metric = "wasserstein2";
  bool plain = false, until_complete = false;
  o.add_options()("metric", po::value(&metric)->default_value("wasserstein2"),
                  "series for the trend: bottleneck, wasserstein1 or wasserstein2")(
      "plain", po::bool_switch(&plain), "one line per frame instead of redrawing the screen")(
      "until-complete", po::bool_switch(&until_complete), "exit when the run has all its planned frames");
  if (!parse(o, args)) return kOk;
  if (metric != "bottleneck" && metric != "wasserstein1" && metric != "wasserstein2")
    throw po::error("unknown --metric '" + metric + "'");
  std::signal(SIGINT, [](int) { interrupted = true; });
  std::signal(SIGTERM, [](int) { interrupted = true; });

  std::optional<std::uint32_t> last_frame;
  std::deque<double> trend;
  std::string run = c.run;
  const std::string key = metric + "/pd" + std::to_string(c.dim) + "/" + c.force;
  int attempts = 0;
  while (!interrupted) {
    try {
      fnet::client::RpcClient rpc(host, port, std::chrono::seconds(10));
      if (run.empty()) run = rpc.call("run.get")["run"].get<std::string>();
      const json info = rpc.call("run.get", {{"run", run}});
      const std::uint32_t planned = info.value("planned_frames", 0u);
      const double rho_end = info["parameters"].is_object() ? info["parameters"].value("final_density", 0.0) : 0.0;
      json sub = {{"run", run}};
      if (last_frame) sub["since"] = *last_frame;
      rpc.call("series.subscribe", sub);
      attempts = 0;
      if (!last_frame) {  // nothing to show until the first frame is analyzed (the run may still be relaxing)
        if (plain)
          std::cout << "watching run " << run << ": waiting for the first analyzed frame" << std::endl;
        else
          std::cout << "\x1b[H\x1b[2Jfnet watch  run " << run
                    << "   (Ctrl-C to leave)\n\nwaiting for the first analyzed frame..." << std::flush;
      }
      double rho_start = -1;
      while (!interrupted) {
        const std::optional<json> n = rpc.next_notification(std::chrono::milliseconds(200));
        if (!n) continue;
        const json& p = (*n)["params"];
        last_frame = p["frame"].get<std::uint32_t>();
        if (rho_start < 0) rho_start = p["rho"].get<double>();
        const json& d = p["distances"];
        if (!d[key].is_null()) {
          trend.push_back(d[key].get<double>());
          if (trend.size() > 60) trend.pop_front();
        }
        if (plain) {
          std::cout << "frame " << *last_frame << " rho " << number(p["rho"]) << " Z " << number(p["z"], 4) << " "
                    << key << " " << number(d[key]) << std::endl;
        } else {
          std::ostringstream s;
          s << "\x1b[H\x1b[2J"
            << "fnet watch  run " << run << "   (Ctrl-C to leave)\n\n";
          s << "frame " << *last_frame << (planned ? " / " + std::to_string(planned - 1) : "") << "   step "
            << p["step"].get<std::uint64_t>() << "\n";
          const double rho = p["rho"].get<double>();
          if (rho_end > rho_start && rho_start > 0) {
            const int filled = std::clamp(static_cast<int>(40 * (rho - rho_start) / (rho_end - rho_start)), 0, 40);
            s << "rho " << std::fixed << std::setprecision(4) << rho << " [" << std::string(filled, '#')
              << std::string(40 - filled, '.') << "] " << rho_end << "\n";
          } else {
            s << "rho " << std::fixed << std::setprecision(4) << rho << "\n";
          }
          s << "Z   " << std::setprecision(3) << p["z"].get<double>() << std::defaultfloat << "\n\n";
          s << "distance from frame "
            << (p["previous"].is_null() ? std::string("-") : std::to_string(p["previous"].get<int>()))
            << "        normal PD0   normal PD1  tangent PD0  tangent PD1\n";
          for (const char* m : {"bottleneck", "wasserstein1", "wasserstein2"}) {
            s << std::setw(28) << std::left << m << std::right;
            for (const char* f : {"normal", "tangential"})
              for (int dim = 0; dim < 2; ++dim)
                s << std::setw(13) << number(d[std::string(m) + "/pd" + std::to_string(dim) + "/" + f], 5);
            s << "\n";
          }
          s << "\n" << key << " trend (last " << trend.size() << "): " << sparkline(trend) << "\n";
          std::cout << s.str() << std::flush;
        }
        if (until_complete && planned && *last_frame + 1 >= planned) return kOk;
      }
    } catch (const fnet::client::ConnectionError& e) {
      if (++attempts > 30) throw;
      if (!plain) std::cout << "\x1b[H\x1b[2J";
      std::cerr << "fnetctl watch: " << e.what() << "; reconnecting...\n";
      for (int k = 0; k < 10 && !interrupted; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  std::cout << "\n";
  return kOk;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string host = "127.0.0.1";
  unsigned long port = 7707;
  // Global options come before the command.
  while (!args.empty() && args[0].rfind("--", 0) == 0 && args[0] != "--help") {
    const std::string flag = args[0];
    if ((flag == "--host" || flag == "--port") && args.size() >= 2) {
      if (flag == "--host")
        host = args[1];
      else {
        try {
          port = std::stoul(args[1]);
          if (port == 0 || port > 65535) throw std::out_of_range("port");
        } catch (const std::exception&) {
          std::cerr << "fnetctl: --port must be an integer in 1..65535, got '" << args[1] << "'\n";
          return kUsage;
        }
      }
      args.erase(args.begin(), args.begin() + 2);
    } else {
      std::cerr << "fnetctl: unknown global option '" << flag << "'\n\n" << kUsageText;
      return kUsage;
    }
  }
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    (args.empty() ? std::cerr : std::cout) << kUsageText;
    return args.empty() ? kUsage : kOk;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  try {
    const auto p = static_cast<unsigned short>(port);
    if (command == "watch") return cmd_watch(host, p, args);
    using Fn = int (*)(Connection&, const std::vector<std::string>&);
    const std::map<std::string, Fn> commands = {{"runs", cmd_runs},
                                                {"query", cmd_query},
                                                {"diagram", cmd_diagram},
                                                {"distance", cmd_distance},
                                                {"status", cmd_status}};
    const auto it = commands.find(command);
    if (it == commands.end()) {
      std::cerr << "fnetctl: unknown command '" << command << "'\n\n" << kUsageText;
      return kUsage;
    }
    Connection connection(host, p);
    return it->second(connection, args);
  } catch (const po::error& e) {
    std::cerr << "fnetctl " << command << ": " << e.what() << " (see fnetctl " << command << " --help)\n";
    return kUsage;
  } catch (const fnet::client::ConnectionError& e) {
    std::cerr << "fnetctl: " << e.what() << " (is fnet-server running? see --host/--port)\n";
    return kUnreachable;
  } catch (const fnet::client::CallError& e) {
    std::cerr << "fnetctl " << command << ": " << e.what() << "\n";
    if (e.code() == fnet::rpc::kUnknownRun || e.code() == fnet::rpc::kUnknownFrame) return kUnknown;
    if (e.code() == fnet::rpc::kInvalidParams) return kUsage;
    return kServerError;
  } catch (const std::exception& e) {
    std::cerr << "fnetctl " << command << ": " << e.what() << "\n";
    return kFailure;
  }
}
