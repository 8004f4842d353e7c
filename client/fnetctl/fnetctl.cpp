// fnetctl: the command-line client of fnet-server.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>

#include <boost/program_options.hpp>

#include "client/fnetctl/cli_options.hpp"
#include "client/fnetctl/commands.hpp"
#include "client/fnetctl/csv_provenance.hpp"
#include "client/fnetctl/value_text.hpp"
#include "client/rpc/rpc_client.hpp"
#include "common/build_info/build_info.hpp"
#include "common/codec/diagram_json.hpp"
#include "common/codec/explain_table.hpp"
#include "proto/json_rpc.hpp"

namespace po = boost::program_options;

namespace fnet::client {
namespace {

constexpr const char* kUsageText =
    "usage: fnetctl [--host H] [--port P] <command> [options]\n"
    "\n"
    "commands:\n"
    "  runs       the runs the server knows, newest activity last\n"
    "  ensembles  the ensembles of realizations, their runs and mean rho_J: [--format table|csv|json]\n"
    "  query      a distance time series: --metric bottleneck|wasserstein1|wasserstein2|wasserstein [--q Q]\n"
    "             [--run R] [--dim 0|1] [--force normal|tangential] [--essential floor|sentinel|separate]\n"
    "             [--from F] [--to T] [--format table|csv|json]; binned over an ensemble's runs:\n"
    "             --ensemble E [--bins WIDTH | --bin-count N] [--axis rho|rho-minus-rho-j];\n"
    "             d_B / d_Wq: --ratio wasserstein1|wasserstein2 (per frame, or of the bin means)\n"
    "  watch      live view of a run (frames, ETA, lag, rho, Z, rho_J, every series as a log sparkline):\n"
    "             [--run R] [--series all|KEYS] [--wait S] [--plain [--metric M] [--dim D] [--force F]]\n"
    "             [--until-complete]; Ctrl-C leaves\n"
    "  diagram    a frame's persistence diagram: --frame K [--run R] [--dim D] [--force F]\n"
    "             [--format table|csv|json]\n"
    "  distance   distance between two frames, also across runs: --frame A --other-frame B --metric M\n"
    "             [--q Q] [--run R] [--other-run R2] [--dim D] [--force F]\n"
    "             [--essential floor|sentinel|separate] [--delta D] [--format table|json]\n"
    "  status     server health: uptime, frames/s, lag, rejected frames with reasons, its build\n"
    "  rescan     serve the stores placed in the server's data directory since it started\n"
    "  blocks     where the network changed: distances cell by cell over a k x k grid between two frames:\n"
    "             --frame A --other-frame B --metric M [--k 2] [--q Q] [--run R] [--dim D] [--force F]\n"
    "             [--essential E] [--format table|csv|json]\n"
    "  explain    the largest change located: the K largest terms of a distance's matching with the grains\n"
    "             that create and destroy each feature: --frame A --other-frame B --metric M [--k 5]\n"
    "             [--q Q] [--run R] [--other-run R2] [--dim D] [--force F] [--essential E] [--format table|json]\n"
    "\n"
    "global options, before or after the command: --host H (default $FNET_HOST, else 127.0.0.1),\n"
    "  --port P (default $FNET_PORT, else 7707), --token-file F (the token a server given --token-file\n"
    "  asks for; default $FNET_TOKEN, the token itself), --tls (a server given --tls-cert; its certificate\n"
    "  verified against the system's authorities) or --tls-ca F (against the PEM certificates in F);\n"
    "  --version prints fnetctl's version and commit\n"
    "exit codes: 0 ok, 1 a failure of fnetctl itself (an answer it cannot read, output it cannot\n"
    "            write), 2 bad usage or parameter, 3 server unreachable, 4 unknown run, frame or\n"
    "            ensemble, 5 other server error\n"
    "Run 'fnetctl <command> --help' for a command's options.\n";

// Connects on first use, so --help and bad options never need a server.
class Connection {
 public:
  explicit Connection(Endpoint at) : at_(std::move(at)) {}
  RpcClient& operator()() {
    if (!client_)
      client_ = std::make_unique<RpcClient>(at_.host, at_.port, std::chrono::seconds(30), at_.token, at_.tls);
    return *client_;
  }

 private:
  Endpoint at_;
  std::unique_ptr<RpcClient> client_;
};

std::string number(const json& v, int significant) {
  return v.is_null() ? "-" : rounded_number(v.get<double>(), significant);
}

double idle_seconds(const json& run) { return run.at("seconds_since_last_frame").get<double>(); }

// The order of `fnetctl runs`: least recently active first, newest activity last, by the
// server's last_activity (Unix seconds, kept in each run's store, so it survives restarts); a run
// whose store predates those times (null) comes first.
double last_activity(const json& run) {
  const auto it = run.find("last_activity");
  return it == run.end() || it->is_null() ? -std::numeric_limits<double>::infinity() : it->get<double>();
}

bool active_before(const json& a, const json& b) {
  if (last_activity(a) != last_activity(b)) return last_activity(a) < last_activity(b);
  return a.at("run").get<std::string>() < b.at("run").get<std::string>();
}

int cmd_runs(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl runs [--format table|json]\n\nThe runs the server knows, newest activity last.\n\noptions");
  std::string format = "table";
  o.add_options()("help,h", "show this help")("format", po::value(&format)->default_value("table"), "table or json");
  if (!parse_command(o, args)) return kOk;
  format_option(format, {"table", "json"});
  json r = rpc().call("runs.list");
  std::vector<json> runs(r["runs"].begin(), r["runs"].end());
  std::sort(runs.begin(), runs.end(), active_before);
  if (format == "json") {
    r["runs"] = runs;
    std::cout << r.dump(2) << "\n";
    return kOk;
  }
  std::printf("%-24s %7s %8s %8s %9s %7s %9s %9s\n", "run", "frames", "rejected", "pending", "rho", "Z", "rho_J",
              "idle(s)");
  for (const json& run : runs)
    std::printf("%-24s %7zu %8zu %8zu %9s %7s %9s %9.1f\n", run["run"].get<std::string>().c_str(),
                run["frames"].get<std::size_t>(), run["rejected"].get<std::size_t>(), run["pending"].get<std::size_t>(),
                number(run["rho"], 5).c_str(), number(run["z"], 4).c_str(),
                number(run.value("rho_j", json(nullptr)), 5).c_str(), idle_seconds(run));
  return kOk;
}

// series.get's arrays as CSV: the columns of fnet-simd's index.csv that the answer carries
// (frame, step, time, rho, z), then previous and value, every number exact.
void print_series_csv(const json& r) {
  const bool steps = r.contains("step") && r.contains("time");
  const json& infinite = r.value("infinite", json());
  std::cout << "frame" << (steps ? ",step,time" : "") << ",rho,z,previous,value\n";
  for (std::size_t k = 0; k < r["frame"].size(); ++k) {
    std::cout << r["frame"][k].get<std::uint32_t>();
    if (steps) std::cout << "," << r["step"][k].get<std::uint64_t>() << "," << exact_number(r["time"][k].get<double>());
    std::cout << "," << exact_number(r["rho"][k].get<double>()) << "," << exact_number(r["z"][k].get<double>()) << ","
              << (r["previous"][k].is_null() ? "" : std::to_string(r["previous"][k].get<std::uint32_t>())) << ","
              << distance_cell(r["value"][k], infinite.is_array() && infinite[k].get<bool>(), CellStyle::csv) << "\n";
  }
}

void print_series_table(const json& r) {
  const json& infinite = r.value("infinite", json());
  std::cout << "run " << r["run"].get<std::string>() << ", " << r["metric"].get<std::string>()
            << (r.contains("ratio") ? " / " + r["ratio"].get<std::string>() : "")
            << (r.contains("q") && r["metric"] == "wasserstein" ? " q=" + exact_number(r["q"].get<double>()) : "")
            << ", PD" << r["dim"].get<int>() << ", " << r["force"].get<std::string>()
            << " forces, essential=" << r["essential"].get<std::string>()
            << (r.contains("ratio") ? "; value[k] = d_B / d_Wq of the step from the previous frame"
                                    : "; value[k] = distance from the previous frame")
            << " (-: none; inf: infinite)\n"
            << std::setw(7) << "frame" << std::setw(11) << "rho" << std::setw(9) << "Z" << std::setw(16) << "value"
            << "\n";
  for (std::size_t k = 0; k < r["frame"].size(); ++k)
    std::cout << std::setw(7) << r["frame"][k].get<std::uint32_t>() << std::setw(11) << number(r["rho"][k], 6)
              << std::setw(9) << number(r["z"][k], 4) << std::setw(16)
              << distance_cell(r["value"][k], infinite.is_array() && infinite[k].get<bool>(), CellStyle::table) << "\n";
}

int cmd_query(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl query --metric M [options]\n"
      "       fnetctl query --ensemble E --metric M [--bins W | --bin-count N] [--axis rho|rho-minus-rho-j]\n"
      "       fnetctl query [--ensemble E] --ratio wasserstein1|wasserstein2 [options]\n\n"
      "A run's series (series.get), or with --ensemble (or --bins, --bin-count, --axis and a --run)\n"
      "the curve binned in rho (ensemble.series): per bin rho_lo, rho_hi, the mean rho, the mean\n"
      "distance over the runs (each run's mean first), its standard error across the runs, the\n"
      "number of runs n_runs and of values n, and the mean Z.\n\noptions");
  SeriesOptions c;
  c.add(o, true, false);
  CurveOptions curve;
  curve.add(o);
  long long from = 0, to = 0;
  std::string format = "table";
  o.add_options()("from", po::value(&from), "first frame index")("to", po::value(&to), "last frame index")(
      "format", po::value(&format)->default_value("table"),
      "table, csv (exact numbers; columns frame,step,time,rho,z,previous,value, or for a binned curve "
      "rho_lo,rho_hi,rho,mean,stderr,n_runs,n,z) or json (the API's answer)");
  po::variables_map vm;
  if (!parse_command(o, args, &vm)) return kOk;
  format_option(format, {"table", "csv", "json"});
  json p = c.checked(vm);
  curve.check(vm, p);
  if (curve.binned(vm)) return curve_query(rpc(), p, format);
  if (vm.count("from")) p["from"] = frame_option("--from", from);
  if (vm.count("to")) p["to"] = frame_option("--to", to);
  if (vm.count("from") && vm.count("to") && from > to)
    throw po::error("--from " + std::to_string(from) + " is after --to " + std::to_string(to));
  const json r = rpc().call("series.get", p);
  if (r["frame"].empty() && (vm.count("from") || vm.count("to"))) {
    // An empty answer for a range: say where the run's frames are rather than print nothing.
    const json summary = rpc().call("run.get", {{"run", r["run"]}});
    const std::string run = r["run"].get<std::string>();
    if (summary["last_frame"].is_null())
      std::cerr << "fnetctl query: run " << run << " has no analyzed frame yet\n";
    else
      std::cerr << "fnetctl query: run " << run << " has no analyzed frame in the range asked ("
                << (vm.count("from") ? "--from " + std::to_string(from) : std::string(""))
                << (vm.count("from") && vm.count("to") ? " " : "")
                << (vm.count("to") ? "--to " + std::to_string(to) : std::string("")) << "): its frames run from "
                << summary["first_frame"].get<std::uint32_t>() << " to the last analyzed frame "
                << summary["last_frame"].get<std::uint32_t>() << "\n";
    return kUnknown;
  }
  if (format == "json")
    std::cout << r.dump() << "\n";
  else if (format == "csv") {
    std::cout << csv_provenance_line(rpc(),
                                     "run " + r["run"].get<std::string>() + ", " + r["metric"].get<std::string>() +
                                         (r.contains("ratio") ? " / " + r["ratio"].get<std::string>() : "") + " PD" +
                                         std::to_string(r["dim"].get<int>()) + ", " + r["force"].get<std::string>() +
                                         " forces",
                                     r["essential"].get<std::string>())
              << "\n";
    print_series_csv(r);
  } else
    print_series_table(r);
  return kOk;
}

int cmd_diagram(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl diagram --frame K [options]\n\n"
      "--format json writes the frame's diagram document, both dimensions, as fnet-analyze diagram\n"
      "does: {\"pd0\", \"pd1\", \"vertices\", \"edges\", \"triangles\"} and where it came from (\"run\",\n"
      "\"frame\", \"force\", \"rho\", \"z\"); fnet-analyze distance reads it.\n\noptions");
  SeriesOptions c;
  c.add(o, false);
  long long frame = 0;
  std::string format = "table";
  o.add_options()("frame", po::value(&frame)->required(), "frame index")(
      "format", po::value(&format)->default_value("table"), "table, csv (birth,death, exact) or json");
  po::variables_map vm;
  if (!parse_command(o, args, &vm)) return kOk;
  format_option(format, {"table", "csv", "json"});
  json p = c.checked(vm);
  p["frame"] = frame_option("--frame", frame);
  if (format == "json") {
    FrameDiagrams diagrams;
    json r;
    for (int dim = 0; dim < 2; ++dim) {
      p["dim"] = dim;
      r = rpc().call("diagram.get", p);
      (dim == 0 ? diagrams.pd0 : diagrams.pd1) = diagram_from_json(r["points"]);
    }
    diagrams.vertices = r["vertices"].get<std::size_t>();
    diagrams.edges = r["edges"].get<std::size_t>();
    diagrams.triangles = r["triangles"].get<std::size_t>();
    json document = to_json(diagrams);
    for (const char* key : {"run", "frame", "force", "rho", "z"}) document[key] = r[key];
    std::cout << document.dump() << "\n";
    return kOk;
  }
  const json r = rpc().call("diagram.get", p);
  if (format == "csv") {
    std::cout << csv_provenance_line(rpc(),
                                     "run " + r["run"].get<std::string>() + " frame " + r["frame"].dump() + ", PD" +
                                         r["dim"].dump() + " of the " + r["force"].get<std::string>() +
                                         " force network",
                                     "none (a diagram)")
              << "\n";
    std::cout << "birth,death\n";
    for (const json& pt : r["points"])
      std::cout << exact_number(pt[0].get<double>()) << "," << exact_number(pt[1].get<double>()) << "\n";
    return kOk;
  }
  std::cout << "run " << r["run"].get<std::string>() << " frame " << r["frame"] << " (rho " << number(r["rho"], 6)
            << "), PD" << r["dim"] << " of the " << r["force"].get<std::string>()
            << " force network: " << r["points"].size() << " points (death -1: never dies)\n";
  for (const json& pt : r["points"]) std::cout << number(pt[0], 10) << "\t" << number(pt[1], 10) << "\n";
  return kOk;
}

// distance.get's answer for the eye: what was compared, then the value and its certificate.
void print_distance_table(const json& r) {
  const bool infinite = r.value("infinite", false);
  std::cout << "run " << r["run"].get<std::string>() << " frame " << r["frame"] << " -> "
            << r.value("other_run", r["run"]).get<std::string>() << " frame " << r["other_frame"] << ": "
            << r["metric"].get<std::string>()
            << (r.contains("q") && r["metric"] == "wasserstein" ? " q=" + exact_number(r["q"].get<double>()) : "")
            << ", PD" << r["dim"] << ", " << r["force"].get<std::string>()
            << " forces, essential=" << r["essential"].get<std::string>() << " (units: the frames' mean force)\n";
  const auto cell = [&](const char* key) { return distance_cell(r.value(key, json()), infinite, CellStyle::table); };
  std::cout << std::left << std::setw(8) << "value" << cell("value") << "\n"
            << std::setw(8) << "lower" << cell("lower") << "\n"
            << std::setw(8) << "upper" << cell("upper") << "\n"
            << std::setw(8) << "exact" << (r.value("exact", false) ? "yes" : "no") << std::right << "\n";
}

int cmd_distance(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl distance --frame A --other-frame B --metric M [options]\n\n"
      "The distance between two frames' diagrams (distance.get): a table of the value, its certified\n"
      "lower and upper bounds and whether it is exact, or with --format json the API's answer, where\n"
      "an infinite distance (--essential separate) is \"value\": null with \"infinite\": true.\n\noptions");
  SeriesOptions c;
  c.add(o, true);
  long long frame = 0, other = 0;
  std::string other_run, format = "table";
  double delta = 0;
  o.add_options()("frame", po::value(&frame)->required(), "first frame")(
      "other-frame", po::value(&other)->required(), "second frame")("other-run", po::value(&other_run),
                                                                    "run of the second frame (default: the first's)")(
      "delta", po::value(&delta)->default_value(0), "0: exact; > 0: certified relative accuracy")(
      "format", po::value(&format)->default_value("table"), "table or json (the API's answer)");
  po::variables_map vm;
  if (!parse_command(o, args, &vm)) return kOk;
  format_option(format, {"table", "json"});
  json p = c.checked(vm);
  p["frame"] = frame_option("--frame", frame);
  p["other_frame"] = frame_option("--other-frame", other);
  if (!other_run.empty()) p["other_run"] = other_run;
  if (!std::isfinite(delta) || delta < 0)
    throw po::error("--delta must be 0 (exact) or a finite relative accuracy > 0, got " + exact_number(delta));
  if (delta > 0) p["delta"] = delta;
  const json r = rpc().call("distance.get", p);
  if (format == "json") {
    std::cout << r.dump() << "\n";
    return kOk;
  }
  print_distance_table(r);
  return kOk;
}

int cmd_explain(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl explain --frame A --other-frame B --metric M [--k K] [options]\n\n"
      "Where the network changed most: the K largest terms of the optimal matching behind the\n"
      "distance (for the bottleneck the first is the term that attains it), each with its two\n"
      "diagram points and the grains of the contacts that create and destroy each feature, read\n"
      "back from the run's store (distance.get with explain: K).\n\noptions");
  SeriesOptions c;
  c.add(o, true);
  long long frame = 0, other = 0, k = 5;
  std::string other_run, format = "table";
  o.add_options()("frame", po::value(&frame)->required(), "first frame")(
      "other-frame", po::value(&other)->required(), "second frame")("other-run", po::value(&other_run),
                                                                    "run of the second frame (default: the first's)")(
      "k", po::value(&k)->default_value(5), "terms: 1 to 1000")("format", po::value(&format)->default_value("table"),
                                                                "table or json (the API's answer)");
  po::variables_map vm;
  if (!parse_command(o, args, &vm)) return kOk;
  format_option(format, {"table", "json"});
  if (k < 1 || k > 1000) throw po::error("--k must be an integer from 1 to 1000, got " + std::to_string(k));
  json p = c.checked(vm);
  p["frame"] = frame_option("--frame", frame);
  p["other_frame"] = frame_option("--other-frame", other);
  p["explain"] = k;
  if (!other_run.empty()) p["other_run"] = other_run;
  const json r = rpc().call("distance.get", p);
  if (format == "json")
    std::cout << r.dump() << "\n";
  else
    write_explain_table(std::cout, r, r["metric"].get<std::string>());
  return kOk;
}

int cmd_rescan(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl rescan\n\n"
      "Has the server read the stores placed in its data directory since it started (e.g. by\n"
      "fnet-analyze store --data-dir, once that has finished): the runs it adopts are served from\n"
      "then on. Exit 5 when a store could not be read (each named).\n\noptions");
  o.add_options()("help,h", "show this help");
  if (!parse_command(o, args)) return kOk;
  const json r = rpc().call("server.rescan");
  if (r["adopted"].empty()) std::cout << "no new store\n";
  for (const json& run : r["adopted"]) std::cout << "adopted run " << run.get<std::string>() << "\n";
  for (const json& problem : r["problems"]) std::cerr << "fnetctl rescan: " << problem.get<std::string>() << "\n";
  return r["problems"].empty() ? kOk : kServerError;
}

int cmd_ensembles(Connection& rpc, const std::vector<std::string>& args) { return ensembles_command(rpc(), args); }

int cmd_status(Connection& rpc, const std::vector<std::string>& args) {
  po::options_description o("usage: fnetctl status [--format table|json]\n\noptions");
  std::string format = "table";
  o.add_options()("help,h", "show this help")("format", po::value(&format)->default_value("table"), "table or json");
  if (!parse_command(o, args)) return kOk;
  format_option(format, {"table", "json"});
  const json s = rpc().call("server.status");
  if (format == "json") {
    std::cout << s.dump(2) << "\n";
    return kOk;
  }
  const json& f = s["frames"];
  // The DDS ingest first: a server that still answers but no longer receives frames must not
  // look healthy.
  const std::string ingest = s.value("ingest", "unknown");
  std::printf("ingest %s\n", ingest.c_str());
  if (s.contains("build"))
    std::printf("fnet-server %s (commit %s), stores %s, %s convention\n",
                s["build"]["version"].get<std::string>().c_str(), s["build"]["commit"].get<std::string>().c_str(),
                s["build"]["store_schema"].get<std::string>().c_str(),
                s["build"]["convention"].get<std::string>().c_str());
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
  // A run whose store takes no writes is failed until it does: unhealthy, like a stopped ingest.
  const json faults = s.contains("stores") ? s["stores"]["faults"] : json::array();
  if (s.contains("stores")) std::printf("stores: %zu open\n", s["stores"]["open"].get<std::size_t>());
  for (const json& fault : faults)
    std::printf("  store fault: run %s: %s (%zu frame(s) wait for the store)\n",
                fault["run"].get<std::string>().c_str(), fault["reason"].get<std::string>().c_str(),
                fault["unstored"].get<std::size_t>());
  if (ingest != "running") {
    std::cerr << "fnetctl status: the server's DDS ingest is " << ingest << ": no new frames arrive\n";
    return kServerError;
  }
  if (!faults.empty()) {
    std::cerr << "fnetctl status: " << faults.size() << " run(s) cannot be stored: their frames wait in memory\n";
    return kServerError;
  }
  return kOk;
}

int run(std::vector<std::string> args) {
  Endpoint at;
  try {
    at = take_endpoint(args, std::getenv("FNET_HOST"), std::getenv("FNET_PORT"), std::getenv("FNET_TOKEN"));
  } catch (const po::error& e) {
    std::cerr << "fnetctl: " << e.what() << "\n";
    return kUsage;
  }
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    (args.empty() ? std::cerr : std::cout) << kUsageText;
    return args.empty() ? kUsage : kOk;
  }
  if (args[0] == "--version") {
    std::cout << fnet::version_line("fnetctl") << "\n";
    return kOk;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  try {
    if (command == "watch") return watch_command(at, args);
    if (command == "blocks") return blocks_command(at, args);
    using Fn = int (*)(Connection&, const std::vector<std::string>&);
    const std::map<std::string, Fn> commands = {
        {"runs", cmd_runs},         {"ensembles", cmd_ensembles}, {"query", cmd_query},   {"diagram", cmd_diagram},
        {"distance", cmd_distance}, {"explain", cmd_explain},     {"status", cmd_status}, {"rescan", cmd_rescan}};
    const auto it = commands.find(command);
    if (it == commands.end()) {
      std::cerr << "fnetctl: unknown command '" << command << "'\n\n" << kUsageText;
      return kUsage;
    }
    Connection connection(at);
    return it->second(connection, args);
  } catch (const po::error& e) {
    std::cerr << "fnetctl " << command << ": " << e.what() << " (see fnetctl " << command << " --help)\n";
    return kUsage;
  } catch (const ConnectionError& e) {
    std::cerr << "fnetctl: " << e.what() << " (is fnet-server running? see --host/--port, FNET_HOST/FNET_PORT)\n";
    return kUnreachable;
  } catch (const CallError& e) {
    std::cerr << "fnetctl " << command << ": " << e.what() << "\n";
    if (e.code() == rpc::kUnknownRun || e.code() == rpc::kUnknownFrame || e.code() == rpc::kUnknownEnsemble)
      return kUnknown;
    if (e.code() == rpc::kInvalidParams) return kUsage;
    return kServerError;
  } catch (const std::exception& e) {
    std::cerr << "fnetctl " << command << ": " << e.what() << "\n";
    return kFailure;
  }
}

}  // namespace
}  // namespace fnet::client

int main(int argc, char** argv) {
  const int code = fnet::client::run(std::vector<std::string>(argv + 1, argv + argc));
  // Output that could not be written (a full disk, a closed pipe) is a failure, not a success.
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
    std::cerr << "fnetctl: cannot write the output: " << std::strerror(errno) << "\n";
    return code == fnet::client::kOk ? fnet::client::kFailure : code;
  }
  return code;
}
