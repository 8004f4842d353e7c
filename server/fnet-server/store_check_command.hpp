// The hidden command by which fnet-server checks a store in a process of its own before it reads
// it (server/registry/store_check.hpp): the server runs itself again as
// `fnet-server --check-store-for PARENT_PID FILE`.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace fnet::server {

// The command that checks a store for this process, the store's path to follow.
std::vector<std::string> check_store_command();

// When argv is the check's command: reads FILE whole as the server would and returns 0, or prints
// why it cannot on stdout and returns 1. nullopt for any other command line.
std::optional<int> run_check_store(int argc, char** argv);

}  // namespace fnet::server
