// A child process owned by a test: started with extra environment, its stdout readable line by
// line, its stderr kept in a file; stopped (SIGTERM, then SIGKILL) and reaped on destruction, so
// a failing test never leaves a process behind.
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace fnet::e2e {

class Process {
 public:
  Process(const std::string& program, const std::vector<std::string>& args, const std::filesystem::path& stderr_file,
          const std::map<std::string, std::string>& env = {});
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;
  ~Process();

  // The next line of stdout, or nullopt on timeout or end of output.
  std::optional<std::string> read_line(std::chrono::milliseconds timeout);
  // Everything the process wrote to stdout until it exits (call after it ended).
  std::string read_rest();
  void signal(int sig);
  // Waits for the exit; returns the exit code (128 + signal if killed), or nullopt on timeout.
  std::optional<int> wait(std::chrono::milliseconds timeout);
  // SIGTERM, a grace period, then SIGKILL; returns the exit code.
  int stop(std::chrono::milliseconds grace = std::chrono::seconds(10));
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  int out_fd_ = -1;
  std::string buffer_;
  std::optional<int> status_;
};

// Environment every DDS process of the tests gets: the loopback configuration.
std::map<std::string, std::string> dds_environment();

}  // namespace fnet::e2e
