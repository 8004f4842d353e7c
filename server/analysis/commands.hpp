// The subcommands of fnet-analyze; each parses its own options and returns the exit code.
#pragma once

#include <string>
#include <vector>

namespace fnet::analyze {

int diagram_command(const std::vector<std::string>& args);
int store_command(const std::vector<std::string>& args);
int publish_command(const std::vector<std::string>& args);
int distance_command(const std::vector<std::string>& args);

}  // namespace fnet::analyze
