// What every fnet-analyze command shares: option parsing, the usage checks, and running one
// command with its exit code.
#include <algorithm>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/codec/command_line.hpp"
#include "server/fnet-analyze/commands.hpp"

namespace fnet::analyze {

std::optional<boost::program_options::variables_map> parse_options(
    const boost::program_options::options_description& options, const std::vector<std::string>& args,
    const boost::program_options::positional_options_description* positional) {
  namespace po = boost::program_options;
  po::variables_map vm;
  auto parser = po::command_line_parser(args).options(options);
  if (positional) parser.positional(*positional);
  const po::parsed_options parsed = parser.run();
  if (!positional) refuse_stray_arguments(parsed);
  po::store(parsed, vm);
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

int run_command(const std::string& name, const Command& command, const std::vector<std::string>& args) {
  try {
    return command(args);
  } catch (const boost::program_options::error& e) {
    std::cerr << "fnet-analyze " << name << ": " << e.what() << " (see --help)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "fnet-analyze " << name << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace fnet::analyze
