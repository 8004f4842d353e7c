// fnet-analyze-io: the fnet-analyze commands that need HDF5 or DDS (store, publish). fnet-analyze
// runs it in its place for them; run directly it takes the same arguments.
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "common/build_info/build_info.hpp"
#include "server/fnet-analyze/commands.hpp"

int main(int argc, char** argv) {
  const std::map<std::string, fnet::analyze::Command> commands = {
      {"store", fnet::analyze::store_command},
      {"publish", fnet::analyze::publish_command},
  };
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && args[0] == "--version") {
    std::cout << fnet::version_line("fnet-analyze-io") << "\n";
    return 0;
  }
  const auto command = args.empty() ? commands.end() : commands.find(args[0]);
  if (command == commands.end()) {
    std::cerr << "usage: fnet-analyze store|publish [options] (run 'fnet-analyze --help')\n";
    return 2;
  }
  args.erase(args.begin());
  return fnet::analyze::run_command(command->first, command->second, args);
}
