// Runs an executable as a child process and collects its exit code, stdout and stderr.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace fnet::testing {

struct ProcessResult {
  int exit_code = -1;  // 128 + signal number if the child was killed by a signal
  std::string out, err;
};

// Runs `program` with `args` (no shell: arguments are passed verbatim). Output is captured through
// files in `scratch`, which must exist.
ProcessResult run_process(const std::string& program, const std::vector<std::string>& args,
                          const std::filesystem::path& scratch);

}  // namespace fnet::testing
