// fnet-analyze: the offline front end of fnet's analysis.
#include <algorithm>
#include <exception>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "server/analysis/commands.hpp"

namespace {

constexpr const char* kUsage =
    "usage: fnet-analyze <command> [options]\n"
    "\n"
    "commands:\n"
    "  diagram   persistence diagrams (PD0, PD1) of one frame's force network\n"
    "  distance  bottleneck or Wasserstein distance between two frames' diagrams\n"
    "  explain   where two frames differ most: the largest terms of a distance, located in grains\n"
    "  store     analyze a recorded run (run file or CSV folder) into a run store, as fnet-server does\n"
    "  publish   replay a recorded run onto DDS, as fnet-simd streams it\n"
    "\n"
    "Run 'fnet-analyze <command> --help' for the options of a command.\n"
    "\n"
    "exit codes: 0 ok, 1 the input could not be analyzed (malformed CSV or JSON, not an HDF5 run\n"
    "            file, an invalid frame), 2 bad usage (unknown option, bad value, missing file)\n";

}  // namespace

namespace fnet::analyze {

std::optional<boost::program_options::variables_map> parse_options(
    const boost::program_options::options_description& options, const std::vector<std::string>& args,
    const boost::program_options::positional_options_description* positional) {
  namespace po = boost::program_options;
  po::variables_map vm;
  auto parser = po::command_line_parser(args).options(options);
  if (positional) parser.positional(*positional);
  po::store(parser.run(), vm);
  if (vm.count("help")) {
    std::cout << options << "\n";
    return std::nullopt;
  }
  po::notify(vm);
  return vm;
}

MetricChoice metric_option(const std::string& name, std::optional<double> q) {
  const bool known = std::find(kMetricNames.begin(), kMetricNames.end(), name) != kMetricNames.end();
  // A known name fails only for its exponent.
  return named_option(known ? "--q" : "--metric", [&] { return parse_metric(name, q); });
}

void require_file(const std::string& what, const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  if (!fs::exists(path)) throw boost::program_options::error(what + " " + path.string() + ": no such file");
  if (fs::is_directory(path))
    throw boost::program_options::error(what + " " + path.string() + ": is a directory, not a file");
}

void require_directory(const std::string& what, const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  if (!fs::exists(path)) throw boost::program_options::error(what + " " + path.string() + ": no such directory");
  if (!fs::is_directory(path)) throw boost::program_options::error(what + " " + path.string() + ": not a directory");
}

}  // namespace fnet::analyze

int main(int argc, char** argv) {
  using Command = std::function<int(const std::vector<std::string>&)>;
  const std::map<std::string, Command> commands = {
      {"diagram", fnet::analyze::diagram_command}, {"distance", fnet::analyze::distance_command},
      {"explain", fnet::analyze::explain_command}, {"store", fnet::analyze::store_command},
      {"publish", fnet::analyze::publish_command},
  };
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    (args.empty() ? std::cerr : std::cout) << kUsage;
    return args.empty() ? 2 : 0;
  }
  const std::string name = args[0];
  args.erase(args.begin());
  const auto command = commands.find(name);
  if (command == commands.end()) {
    std::cerr << "fnet-analyze: unknown command '" << name << "'\n\n" << kUsage;
    return 2;
  }
  try {
    return command->second(args);
  } catch (const boost::program_options::error& e) {
    std::cerr << "fnet-analyze " << name << ": " << e.what() << " (see --help)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "fnet-analyze " << name << ": " << e.what() << "\n";
    return 1;
  }
}
