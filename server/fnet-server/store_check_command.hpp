// The hidden command by which fnet-server checks stores in a process of its own before it reads
// them (server/registry/store_check.hpp): the server runs itself again as
// `fnet-server --check-store-for PARENT_PID FILE...`.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace fnet::server {

// The command that checks stores for this process, their paths to follow.
std::vector<std::string> check_store_command();

// When argv is the check's command: reads each FILE whole as the server would and answers it on a
// line of stdout (kStorePassed, or why it cannot be read), then returns 0. nullopt for any other
// command line.
std::optional<int> run_check_store(int argc, char** argv);

}  // namespace fnet::server
