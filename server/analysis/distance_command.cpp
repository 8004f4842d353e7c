// fnet-analyze distance: bottleneck or Wasserstein distance between two diagrams of fnet-analyze diagram.
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/analysis/frame_analysis.hpp"
#include "common/codec/diagram_json.hpp"
#include "common/codec/distance_json.hpp"
#include "common/distance/essential_convention.hpp"
#include "server/analysis/commands.hpp"

namespace po = boost::program_options;

namespace fnet::analyze {

namespace {

Diagram read_diagram(const std::string& path, int dim) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": not JSON: " + e.what());
  }
  const std::string key = dim == 0 ? "pd0" : "pd1";
  if (!doc.is_object() || !doc.contains(key)) throw std::runtime_error(path + ": no \"" + key + "\" array");
  try {
    return diagram_from_json(doc[key]);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + " " + key + ": " + e.what());
  }
}

}  // namespace

int distance_command(const std::vector<std::string>& args) {
  po::options_description options(
      "usage: fnet-analyze distance A.json B.json --metric bottleneck|wasserstein1|wasserstein2|wasserstein\n"
      "                             [--q Q] [--dim 0|1] [--delta D] [--essential floor|sentinel|separate]\n"
      "\n"
      "Distance between the diagrams of two files printed by 'fnet-analyze diagram'. L-infinity ground\n"
      "metric; a point may match the diagonal at (birth - death) / 2. Prints\n"
      "  {\"value\": v, \"lower\": l, \"upper\": u, \"exact\": true|false, \"essential\": convention, \"seconds\": t}\n"
      "With --delta 0 (default) the distance is exact and lower = upper = value. With --delta D > 0 the\n"
      "value is the cost of an actual matching and upper - lower <= D * lower (bottleneck: upper <=\n"
      "(1 + D) * lower); the Wasserstein distances answer exactly whatever D (lower = upper). Under\n"
      "--essential separate the distance is infinite when the diagrams have different numbers of\n"
      "never-dying classes: \"value\": null, \"infinite\": true and the reason.\n"
      "\n"
      "options");
  std::string metric, essential = "floor";
  std::vector<std::string> files;
  double q = 0, delta = 0;
  int dim = 1;
  options.add_options()("help,h", "show this help")(
      "metric", po::value(&metric)->required(), "bottleneck, wasserstein1, wasserstein2, or wasserstein (with --q)")(
      "q", po::value(&q), "the exponent of --metric wasserstein: a real number >= 1")(
      "dim", po::value(&dim)->default_value(1), "which diagram: 0 (pd0) or 1 (pd1)")(
      "delta", po::value(&delta)->default_value(0), "0: exact; D > 0: certified relative error D")(
      "essential", po::value(&essential)->default_value("floor"),
      "never-dying classes: floor (die at 0), sentinel (death -1 literally), separate (matched among themselves)")(
      "files", po::value(&files), "A.json B.json");
  po::positional_options_description positional;
  positional.add("files", 2);
  const auto vm = parse_options(options, args, &positional);
  if (!vm) return 0;
  if (files.size() != 2) throw po::error("two diagram files are required");
  if (dim != 0 && dim != 1) throw po::error("--dim must be 0 or 1");
  if (!std::isfinite(delta) || delta < 0) throw po::error("--delta must be a finite number >= 0");
  if (metric == "wasserstein1") {
    if (vm->count("q") && q != 1) throw po::error("--q contradicts --metric wasserstein1");
    q = 1;
  } else if (metric == "wasserstein2") {
    if (vm->count("q") && q != 2) throw po::error("--q contradicts --metric wasserstein2");
    q = 2;
  } else if (metric == "wasserstein") {
    if (!vm->count("q")) throw po::error("--metric wasserstein needs --q");
    if (!std::isfinite(q) || q < 1) throw po::error("--q must be a finite number >= 1");
  } else if (metric != "bottleneck") {
    throw po::error("unknown --metric '" + metric + "' (bottleneck, wasserstein1, wasserstein2, wasserstein)");
  } else if (vm->count("q")) {
    throw po::error("--q applies to the Wasserstein metrics only");
  }
  const EssentialConvention convention = parse_essential_convention(essential);

  const Diagram a = read_diagram(files[0], dim), b = read_diagram(files[1], dim);
  const auto start = std::chrono::steady_clock::now();
  const DistanceMetric distance =
      metric == "bottleneck" ? DistanceMetric::bottleneck() : DistanceMetric::wasserstein(q);
  const DistanceResult result = diagram_distance(a, b, distance, convention, delta);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json out = to_json(result);
  out["metric"] = metric;
  if (metric != "bottleneck") out["q"] = q;
  out["dim"] = dim;
  out["essential"] = std::string(to_string(convention));
  out["seconds"] = seconds;
  std::cout << out.dump() << "\n";
  return 0;
}

}  // namespace fnet::analyze
