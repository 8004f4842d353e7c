#include "server/registry/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <sys/wait.h>
#include <utility>

namespace fnet::server {
namespace {

// posix_spawn's attribute and file-action objects, destroyed with their scope.
struct SpawnAttributes {
  posix_spawnattr_t a;
  SpawnAttributes() { posix_spawnattr_init(&a); }
  ~SpawnAttributes() { posix_spawnattr_destroy(&a); }
};
struct SpawnActions {
  posix_spawn_file_actions_t a;
  SpawnActions() { posix_spawn_file_actions_init(&a); }
  ~SpawnActions() { posix_spawn_file_actions_destroy(&a); }
};

constexpr std::size_t kReadAtOnce = 64 << 10;  // a child that writes on and on is read in turns

std::runtime_error failure(const std::string& what, int error) {
  return std::runtime_error(what + ": " + std::strerror(error));
}

}  // namespace

ChildProcess::ChildProcess(const std::string& program, const std::vector<std::string>& argv) {
  int ends[2];
  if (pipe2(ends, O_CLOEXEC) != 0) throw failure("pipe", errno);
  output_ = ends[0];
  fcntl(output_, F_SETFL, fcntl(output_, F_GETFL) | O_NONBLOCK);
  SpawnActions actions;
  posix_spawn_file_actions_addopen(&actions.a, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions.a, ends[1], 1);
  posix_spawn_file_actions_addopen(&actions.a, 2, "/dev/null", O_WRONLY, 0);
  // The server's sockets and files stay its own (a listening socket held by a child would keep
  // the port after the server ends).
  posix_spawn_file_actions_addclosefrom_np(&actions.a, 3);
  // The child starts with default signal dispositions and nothing blocked, whatever the thread
  // that starts it has set.
  SpawnAttributes attributes;
  sigset_t none, all;
  sigemptyset(&none);
  sigfillset(&all);
  posix_spawnattr_setsigmask(&attributes.a, &none);
  posix_spawnattr_setsigdefault(&attributes.a, &all);
  posix_spawnattr_setflags(&attributes.a, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const int error = posix_spawn(&pid_, program.c_str(), &actions.a, &attributes.a, args.data(), environ);
  close(ends[1]);
  if (error != 0) {
    pid_ = -1;
    close(output_);
    throw failure("cannot run " + program, error);
  }
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : pid_(std::exchange(other.pid_, -1)), output_(std::exchange(other.output_, -1)) {}

ChildProcess::~ChildProcess() {
  kill();
  if (output_ >= 0) close(output_);
}

std::string ChildProcess::read_output() {
  std::string out;
  char buffer[4096];
  while (output_ >= 0 && out.size() < kReadAtOnce) {
    const ssize_t n = read(output_, buffer, sizeof buffer);
    if (n > 0) {
      out.append(buffer, static_cast<std::size_t>(n));
    } else if (n < 0 && errno == EAGAIN) {
      break;
    } else if (n == 0 || errno != EINTR) {
      close(output_);
      output_ = -1;
    }
  }
  return out;
}

std::optional<int> ChildProcess::exited() {
  if (pid_ < 0) return std::nullopt;
  int status = 0;
  pid_t got;
  while ((got = waitpid(pid_, &status, WNOHANG)) < 0 && errno == EINTR) {
  }
  if (got == 0) return std::nullopt;
  pid_ = -1;
  return got > 0 ? status : W_EXITCODE(127, 0);  // not ours to wait for: it is taken as a failure
}

void ChildProcess::kill() {
  if (pid_ < 0) return;
  ::kill(pid_, SIGKILL);
  while (waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
}

}  // namespace fnet::server
