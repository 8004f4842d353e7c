// The subcommands of fnet-analyze; each parses its own options and returns the exit code.
#pragma once

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/analysis/metric_vocabulary.hpp"

namespace fnet::analyze {

// Parses a command's options: empty after printing --help (the command then exits 0); throws
// boost::program_options::error on bad or missing options.
std::optional<boost::program_options::variables_map> parse_options(
    const boost::program_options::options_description& options, const std::vector<std::string>& args,
    const boost::program_options::positional_options_description* positional = nullptr);

// Runs `parse`, one of the vocabulary's parsers (which throw std::invalid_argument), and rethrows
// its error as a usage error naming `flag`.
template <class Parse>
auto named_option(const std::string& flag, Parse parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    throw boost::program_options::error(flag + ": " + e.what());
  }
}

// --metric and --q by the shared vocabulary; the usage error names the flag at fault.
MetricChoice metric_option(const std::string& name, std::optional<double> q);

using Command = std::function<int(const std::vector<std::string>&)>;

// Runs the command `name` with its arguments and returns the exit code: the command's own, 2 after
// a usage error, 1 after any other, each with the message on stderr.
int run_command(const std::string& name, const Command& command, const std::vector<std::string>& args);

int diagram_command(const std::vector<std::string>& args);
int distance_command(const std::vector<std::string>& args);
int explain_command(const std::vector<std::string>& args);
// In fnet-analyze-io.
int store_command(const std::vector<std::string>& args);
int publish_command(const std::vector<std::string>& args);

}  // namespace fnet::analyze
