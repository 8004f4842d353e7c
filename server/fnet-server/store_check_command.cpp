#include "server/fnet-server/store_check_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <exception>
#include <iostream>
#include <string_view>
#include <sys/prctl.h>
#include <sys/resource.h>

#include "common/store/analysis_store.hpp"
#include "common/store/hdf5_io.hpp"
#include "server/registry/store_check.hpp"

namespace fnet::server {
namespace {

constexpr std::string_view kFlag = "--check-store-for";

}  // namespace

std::vector<std::string> check_store_command() {
  // The running program's own image, even if its file was replaced since it started.
  return {"/proc/self/exe", std::string(kFlag), std::to_string(getpid())};
}

std::optional<int> run_check_store(int argc, char** argv) {
  if (argc < 4 || argv[1] != kFlag) return std::nullopt;
  // A check never outlives the server that waits for it, even one killed before this line.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (std::to_string(getppid()) != argv[2]) return 1;
  const rlimit no_core{0, 0};  // a crash inside HDF5 is a refusal, not a core file
  setrlimit(RLIMIT_CORE, &no_core);
  h5::quiet();
  for (int k = 3; k < argc; ++k) {
    std::string answer = kStorePassed;
    try {
      read_whole_store_in_data_dir(argv[k]);
    } catch (const std::exception& e) {
      answer = e.what();
      std::replace(answer.begin(), answer.end(), '\n', ' ');
    }
    std::cout << answer << std::endl;  // flushed: the server times each store from the answer before
  }
  return 0;
}

}  // namespace fnet::server
