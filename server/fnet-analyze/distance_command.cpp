// fnet-analyze distance: bottleneck or Wasserstein distance between the diagrams of two diagram documents.
#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/analysis/metric_vocabulary.hpp"
#include "common/codec/diagram_json.hpp"
#include "common/codec/distance_json.hpp"
#include "common/codec/file_text.hpp"
#include "common/distance/essential_convention.hpp"
#include "server/fnet-analyze/commands.hpp"
#include "server/sources/input_paths.hpp"

namespace po = boost::program_options;

namespace fnet::analyze {

namespace {

Diagram read_diagram(const std::string& path, int dim) {
  const std::optional<FileText> text = FileText::read(path);
  if (!text) throw std::runtime_error("cannot open " + path);
  try {
    return parse_document_diagram(text->view(), dim, path);  // JsonInputError names the path
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace

int distance_command(const std::vector<std::string>& args) {
  po::options_description options(
      "usage: fnet-analyze distance A.json B.json --metric bottleneck|wasserstein1|wasserstein2|wasserstein\n"
      "                             [--q Q] [--dim 0|1] [--delta D] [--essential floor|sentinel|separate]\n"
      "\n"
      "Distance between the diagrams of two diagram documents ({\"pd0\": [...], \"pd1\": [...]}, as\n"
      "'fnet-analyze diagram' and 'fnetctl diagram --format json' write them). L-infinity ground\n"
      "metric; a point may match the diagonal at (birth - death) / 2. Prints\n"
      "  {\"value\": v, \"lower\": l, \"upper\": u, \"exact\": true|false, \"metric\", \"q\"?, \"dim\",\n"
      "   \"essential\": convention, \"seconds\": t}\n"
      "With --delta 0 (default) the distance is exact and lower = upper = value. With --delta D > 0 the\n"
      "value is the cost of an actual matching and upper - lower <= D * lower (bottleneck: upper <=\n"
      "(1 + D) * lower); W1 and W2 stop as soon as the matching in hand and the dual bound are\n"
      "within D, other q answer exactly (lower = upper). Under\n"
      "--essential separate the distance is infinite when the diagrams have different numbers of\n"
      "never-dying classes: \"value\": null, \"infinite\": true and the reason.\n"
      "\n"
      "options");
  std::string metric, essential = "floor";
  std::vector<std::string> files;
  double q = 0, delta = 0;
  long long dim = kDefaultDim;
  options.add_options()("help,h", "show this help")(
      "metric", po::value(&metric)->required(), "bottleneck, wasserstein1, wasserstein2, or wasserstein (with --q)")(
      "q", po::value(&q), "the exponent of --metric wasserstein: a real number >= 1")(
      "dim", po::value(&dim)->default_value(kDefaultDim),
      "which diagram: 0 (pd0) or 1 (pd1); the default is the API's, proto/api.md")(
      "delta", po::value(&delta)->default_value(0), "0: exact; D > 0: certified relative error D")(
      "essential", po::value(&essential)->default_value("floor"),
      "never-dying classes: floor (die at 0), sentinel (death -1 literally), separate (matched among themselves)")(
      "files", po::value(&files), "A.json B.json");
  po::positional_options_description positional;
  positional.add("files", 2);
  const auto vm = parse_options(options, args, &positional);
  if (!vm) return 0;
  if (files.size() != 2) throw po::error("two diagram files are required");
  const MetricChoice choice = metric_option(metric, vm->count("q") ? std::optional(q) : std::nullopt);
  const int d = named_option("--dim", [&] { return check_dim(dim); });
  const EssentialConvention convention =
      named_option("--essential", [&] { return parse_essential_convention(essential); });
  if (!std::isfinite(delta) || delta < 0) throw po::error("--delta must be a finite number >= 0");
  for (const std::string& file : files) sources::require_file("diagram file", file);

  const Diagram a = read_diagram(files[0], d), b = read_diagram(files[1], d);
  const auto start = std::chrono::steady_clock::now();
  const DistanceResult result = choice_distance(a, b, choice, convention, delta);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json out = to_json(result);
  out["metric"] = choice.name;
  if (choice.q) out["q"] = *choice.q;
  out["dim"] = d;
  out["essential"] = std::string(to_string(convention));
  out["seconds"] = seconds;
  std::cout << out.dump() << "\n";
  return 0;
}

}  // namespace fnet::analyze
