// fnet-analyze: the offline front end of fnet's analysis.
#include <malloc.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

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

// store and publish need HDF5 and DDS, whose libraries (and theirs: TLS, Kerberos, LDAP...) take
// several times longer to load than a 2 000-grain diagram takes to compute. They live in
// fnet-analyze-io, installed next to this program, which runs them in its place.
int run_in_io_binary(const std::string& name, char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path io = (ec ? std::filesystem::path(argv[0]) : self).parent_path() / "fnet-analyze-io";
  std::string program = io.string();
  argv[0] = program.data();
  execv(program.c_str(), argv);
  std::cerr << "fnet-analyze " << name << ": cannot run " << program << ": " << std::strerror(errno) << "\n";
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  // Large blocks from the heap, kept there: what one stage frees (a file's text, a vector that
  // grew) the next reuses, instead of unmapping it and faulting fresh pages in one by one.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  const std::map<std::string, fnet::analyze::Command> commands = {
      {"diagram", fnet::analyze::diagram_command},
      {"distance", fnet::analyze::distance_command},
      {"explain", fnet::analyze::explain_command},
  };
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    (args.empty() ? std::cerr : std::cout) << kUsage;
    return args.empty() ? 2 : 0;
  }
  const std::string name = args[0];
  if (name == "store" || name == "publish") return run_in_io_binary(name, argv);
  args.erase(args.begin());
  const auto command = commands.find(name);
  if (command == commands.end()) {
    std::cerr << "fnet-analyze: unknown command '" << name << "'\n\n" << kUsage;
    return 2;
  }
  return fnet::analyze::run_command(name, command->second, args);
}
