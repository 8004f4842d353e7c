// A child process the server runs and never leaves behind: started with posix_spawn (no fork of
// the multithreaded server), its stdout into a pipe the parent reads (its answer), its stdin and
// stderr /dev/null (a sanitizer's or HDF5's own report is not an answer), no other descriptor
// inherited; killed (SIGKILL) and reaped when its owner lets it go, whatever it is doing.
#pragma once

#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace fnet::server {

class ChildProcess {
 public:
  // Runs `program` with `argv` (argv[0] included). Throws std::runtime_error when it cannot.
  ChildProcess(const std::string& program, const std::vector<std::string>& argv);
  ~ChildProcess();
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&&) = delete;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  // The read end of the output pipe (non-blocking); -1 once the child closed its end.
  int output() const { return output_; }
  // What the child wrote since the last call (what the pipe holds now, up to 64 KiB); closes the
  // read end at end of file.
  std::string read_output();
  // The child's wait status once it has exited (reaped then), nullopt while it runs.
  std::optional<int> exited();
  // SIGKILL, then reaped.
  void kill();

 private:
  pid_t pid_ = -1;  // -1 once reaped
  int output_ = -1;
};

}  // namespace fnet::server
