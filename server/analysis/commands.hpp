// The subcommands of fnet-analyze; each parses its own options and returns the exit code.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

namespace fnet::analyze {

// Parses a command's options: empty after printing --help (the command then exits 0); throws
// boost::program_options::error on bad or missing options.
std::optional<boost::program_options::variables_map> parse_options(
    const boost::program_options::options_description& options, const std::vector<std::string>& args,
    const boost::program_options::positional_options_description* positional = nullptr);

int diagram_command(const std::vector<std::string>& args);
int store_command(const std::vector<std::string>& args);
int publish_command(const std::vector<std::string>& args);
int distance_command(const std::vector<std::string>& args);

}  // namespace fnet::analyze
