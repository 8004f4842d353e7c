// fnet-analyze: the offline front end of fnet's analysis.
#include <malloc.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <sys/mman.h>
#include <vector>

#include "common/build_info/build_info.hpp"
#include "server/fnet-analyze/commands.hpp"

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
    "            file, an invalid frame), 2 bad usage (unknown option, bad value, missing file),\n"
    "            3 publish: a subscriber may lack frames (it had not acknowledged every frame\n"
    "            after --ack-timeout, or went away during the run, or a fnet-server had not\n"
    "            stored them by then), 4 publish: a fnet-server cannot store the run\n";

// store and publish need HDF5 and DDS, whose libraries (and theirs: TLS, Kerberos, LDAP...) take
// several times longer to load than a 2 000-grain diagram takes to compute. They live in
// fnet-analyze-io, installed next to this program, which runs them in its place.
int run_in_io_binary(const std::string& name, char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path io = (ec ? std::filesystem::path(argv[0]) : self).parent_path() / "fnet-analyze-io";
  std::string program = io.string();
  argv[0] = program.data();
  // Without /proc and started through PATH, argv[0] names no directory: look along PATH too.
  (io.has_parent_path() ? execv : execvp)(program.c_str(), argv);
  std::cerr << "fnet-analyze " << name << ": cannot run " << program << ": " << std::strerror(errno) << "\n";
  return 1;
}

// A 40 000-grain frame touches ~11 MiB, ~2 800 fresh 4 KiB pages, each a page fault costing
// microseconds on a virtual machine: more than the persistence. Large blocks come from the heap and
// stay there (what one stage frees, the next reuses), and the heap, grown once by 64 MiB of address
// space (untouched, so free), is offered transparent huge pages: 2 MiB per fault where the kernel
// grants them. Only advice: without THP nothing changes.
void prepare_heap() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const auto start = reinterpret_cast<std::uintptr_t>(sbrk(0));
  mallopt(M_TOP_PAD, 64 << 20);
  void* volatile block = std::malloc(1 << 20);  // volatile: a malloc freed unused may be elided
  std::free(block);
  mallopt(M_TOP_PAD, 128 << 10);  // glibc's default, for later growth
  const auto end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t first = (start + kHuge - 1) & ~(kHuge - 1), last = end & ~(kHuge - 1);
  const auto failed = reinterpret_cast<std::uintptr_t>(reinterpret_cast<void*>(-1));  // sbrk's error
  if (start != failed && end != failed && last > first)
    madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

}  // namespace

int main(int argc, char** argv) {
  prepare_heap();
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
  if (args[0] == "--version") {
    std::cout << fnet::version_line("fnet-analyze") << "\n";
    return 0;
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
