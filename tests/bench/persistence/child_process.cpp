#include "tests/bench/persistence/child_process.hpp"

#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <sys/resource.h>
#include <sys/wait.h>

namespace fnet::bench {

ChildRun run_in_child(const std::function<void(std::FILE*)>& body) {
  ChildRun run;
  run.output = std::tmpfile();
  if (!run.output) throw std::runtime_error("tmpfile failed");
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    int code = 0;
    try {
      body(run.output);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "child failed: %s\n", e.what());
      code = 1;
    }
    std::fflush(run.output);
    std::fflush(stderr);
    _exit(code);  // no atexit handlers or static destructors of the parent's state
  }
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) throw std::runtime_error("wait4 failed");
  run.peak_rss_kib = usage.ru_maxrss;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    run.ok = true;
  } else if (WIFSIGNALED(status)) {
    run.failure = "killed by signal " + std::to_string(WTERMSIG(status));
  } else {
    run.failure = "exit " + std::to_string(WEXITSTATUS(status));
  }
  std::rewind(run.output);
  return run;
}

}  // namespace fnet::bench
