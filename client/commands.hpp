// fnetctl's commands that live in their own files.
#pragma once

#include <string>
#include <vector>

#include "client/cli_options.hpp"

namespace fnet::client {

int watch_command(const Endpoint& at, const std::vector<std::string>& args);
int blocks_command(const Endpoint& at, const std::vector<std::string>& args);

}  // namespace fnet::client
