// fnet-simd: the simulation daemon. Runs the paper's compression protocol and hands every frame
// to the sinks selected on the command line.
#include <signal.h>

#include <atomic>
#include <csignal>
#include <iostream>

#include "server/fnet-simd/ensemble_launch.hpp"
#include "server/fnet-simd/simd_options.hpp"
#include "server/fnet-simd/single_run.hpp"

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

}  // namespace

int main(int argc, char** argv) try {
  // Handlers first: an ensemble starts its realizations with these signals blocked, so that a stop
  // that comes while one is starting is kept until here and then ends it cleanly at a checkpoint.
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  {
    sigset_t stops;
    sigemptyset(&stops);
    sigaddset(&stops, SIGINT);
    sigaddset(&stops, SIGTERM);
    sigprocmask(SIG_UNBLOCK, &stops, nullptr);
  }
  std::optional<fnet::sim::SimdOptions> options = fnet::sim::parse_simd_options(argc, argv);
  if (!options) return 0;  // --help, --version
  if (options->vm.count("seeds")) return fnet::sim::run_as_ensemble(*options, g_stop);
  return fnet::sim::run_single(std::move(*options), g_stop);
} catch (const boost::program_options::error& e) {
  std::cerr << "fnet-simd: " << e.what() << " (see --help)\n";
  return 2;
} catch (const std::invalid_argument& e) {  // a bad parameter value or config file
  std::cerr << "fnet-simd: " << e.what() << "\n";
  return 2;
} catch (const std::exception& e) {
  std::cerr << "fnet-simd: " << e.what() << "\n";
  return 1;
}
