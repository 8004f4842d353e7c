#include "server/fnet-simd/ensemble_runner.hpp"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <utility>

namespace fnet::sim {
namespace {

using Clock = std::chrono::steady_clock;

class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  Fd(Fd&& o) noexcept : fd_(o.release()) {}
  Fd& operator=(Fd&& o) noexcept {
    if (this != &o) reset(o.release());
    return *this;
  }
  ~Fd() { reset(); }
  int get() const { return fd_; }
  int release() { return std::exchange(fd_, -1); }
  void reset(int fd = -1) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
  }

 private:
  int fd_;
};

struct Child {
  const Realization* run = nullptr;
  pid_t pid = -1;
  Fd events;
  std::string pending;  // a partial event line
  std::size_t frames_done = 0;
};

// One line per state change of a realization, stamped with the seconds since the ensemble began.
class Reporter {
 public:
  template <class... A>
  void line(const Realization& r, const char* format, A... args) {
    const double t = std::chrono::duration<double>(Clock::now() - start_).count();
    std::string text(static_cast<std::size_t>(std::max(std::snprintf(nullptr, 0, format, args...), 0)) + 1, '\0');
    std::snprintf(text.data(), text.size(), format, args...);
    std::fprintf(stderr, "fnet-simd: [%7.1fs] %s: %s\n", t, r.run_id.c_str(), text.c_str());
  }

 private:
  Clock::time_point start_ = Clock::now();
};

std::string last_line(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

[[noreturn]] void exec_failed(const char* what) {
  const char* e = std::strerror(errno);
  (void)!::write(2, what, std::strlen(what));
  (void)!::write(2, e, std::strlen(e));
  (void)!::write(2, "\n", 1);
  ::_exit(127);
}

Child spawn(const Realization& r) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  Fd read_end(pipe_fds[0]), write_end(pipe_fds[1]);
  Fd log(::open(r.log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644));
  if (log.get() < 0) throw std::runtime_error(r.log.string() + ": cannot open log: " + std::strerror(errno));
  std::vector<std::string> args{"fnet-simd"};
  args.insert(args.end(), r.args.begin(), r.args.end());
  args.insert(args.end(), {"--events-fd", std::to_string(kEventsFd)});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();
  // The stop signals are blocked from before the fork (a signal taken between fork and exec would
  // run the parent's handler in the child's copy and be lost with it) and stay blocked across exec
  // until the child has its handlers: a stop sent right after the start is then a clean stop.
  sigset_t stops, before;
  sigemptyset(&stops);
  sigaddset(&stops, SIGINT);
  sigaddset(&stops, SIGTERM);
  sigprocmask(SIG_BLOCK, &stops, &before);
  const pid_t pid = ::fork();
  if (pid != 0) sigprocmask(SIG_SETMASK, &before, nullptr);
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    // Only async-signal-safe calls until exec.
    // A parent that dies (even by SIGKILL) stops its children cleanly rather than orphaning them.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(130);
    if (::dup2(log.get(), 2) < 0) exec_failed("fnet-simd: dup2: ");
    if (write_end.get() == kEventsFd) {
      if (::fcntl(kEventsFd, F_SETFD, 0) != 0) exec_failed("fnet-simd: fcntl: ");
    } else if (::dup2(write_end.get(), kEventsFd) < 0) {
      exec_failed("fnet-simd: dup2: ");
    }
    ::execv("/proc/self/exe", argv.data());
    exec_failed("fnet-simd: cannot execute /proc/self/exe: ");
  }
  Child c;
  c.run = &r;
  c.pid = pid;
  c.events = std::move(read_end);
  c.frames_done = r.first_frame;
  return c;
}

// The complete event lines the child has written so far.
void take_events(Child& c, Reporter& out, bool frame_lines) {
  for (std::size_t end; (end = c.pending.find('\n')) != std::string::npos; c.pending.erase(0, end + 1)) {
    const std::string event = c.pending.substr(0, end);
    if (event.rfind("frame ", 0) == 0) {
      c.frames_done = std::stoul(event.substr(6));
      if (frame_lines) out.line(*c.run, "frame %zu/%zu", c.frames_done, c.run->frames);
    }
  }
}

// Reads what the child reported; false at end of file (the child exited).
bool read_events(Child& c, Reporter& out, bool frame_lines) {
  char buf[256];
  const ssize_t n = ::read(c.events.get(), buf, sizeof buf);
  if (n == 0) return false;
  if (n < 0) return errno == EINTR || errno == EAGAIN;
  c.pending.append(buf, static_cast<std::size_t>(n));
  take_events(c, out, frame_lines);
  return true;
}

}  // namespace

int run_ensemble(const std::string& name, const std::vector<Realization>& runs, unsigned jobs, bool frame_lines,
                 const std::atomic<bool>& stop) {
  Reporter out;
  std::vector<Child> running;
  std::vector<std::string> failed, stopped;
  std::size_t next = 0, finished = 0, skipped = 0, not_started = 0;
  bool stop_sent = false;
  while (true) {
    while (!stop && running.size() < jobs && next < runs.size()) {
      const Realization& r = runs[next++];
      if (r.complete) {
        out.line(r, "already finished (checkpoint %s holds all %zu frames): not run again", r.checkpoint.c_str(),
                 r.frames);
        ++skipped;
        continue;
      }
      running.push_back(spawn(r));
      if (r.resume)
        out.line(r, "started (pid %d): resuming from its checkpoint, %zu of %zu frames done", running.back().pid,
                 r.first_frame, r.frames);
      else
        out.line(r, "started (pid %d): seed %llu from the start, log %s", running.back().pid,
                 static_cast<unsigned long long>(r.seed), r.log.c_str());
    }
    if (running.empty()) break;
    if (stop && !stop_sent) {
      for (const Child& c : running) ::kill(c.pid, SIGTERM);
      stop_sent = true;
    }
    std::vector<pollfd> fds;
    for (const Child& c : running) fds.push_back({c.events.get(), POLLIN, 0});
    ::poll(fds.data(), fds.size(), 100);
    for (std::size_t k = 0; k < running.size(); ++k)
      if (running[k].events.get() >= 0 && (fds[k].revents & (POLLIN | POLLHUP)))
        if (!read_events(running[k], out, frame_lines)) running[k].events.reset();
    for (auto it = running.begin(); it != running.end();) {
      int status = 0;
      if (::waitpid(it->pid, &status, WNOHANG) != it->pid) {
        ++it;
        continue;
      }
      if (it->events.get() >= 0) {  // what it wrote before it exited is still in the pipe
        ::fcntl(it->events.get(), F_SETFL, O_NONBLOCK);
        char buf[256];
        for (ssize_t n; (n = ::read(it->events.get(), buf, sizeof buf)) > 0;)
          it->pending.append(buf, static_cast<std::size_t>(n));
        take_events(*it, out, frame_lines);
      }
      const Realization& r = *it->run;
      if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        out.line(r, "finished (%zu frames)", r.frames);
        ++finished;
      } else if (WIFEXITED(status) && WEXITSTATUS(status) == 130 && stop) {
        out.line(r, "stopped (exit 130) after %zu of %zu frames; checkpoint %s", it->frames_done, r.frames,
                 r.checkpoint.c_str());
        stopped.push_back(r.run_id);
      } else {
        char why[64];
        if (WIFEXITED(status))
          std::snprintf(why, sizeof why, "exit %d", WEXITSTATUS(status));
        else
          std::snprintf(why, sizeof why, "killed by signal %d", WTERMSIG(status));
        const std::string said = last_line(r.log);
        out.line(r, "failed (%s)%s%s (log %s)", why, said.empty() ? "" : ": ", said.c_str(), r.log.c_str());
        failed.push_back(r.run_id + " (" + why + ")");
      }
      it = running.erase(it);
    }
  }
  not_started = runs.size() - next;
  std::string summary = "fnet-simd: ensemble " + name + ": " + std::to_string(finished + skipped) + " of " +
                        std::to_string(runs.size()) + " finished";
  if (skipped) summary += " (" + std::to_string(skipped) + " before this command)";
  if (!stopped.empty() || not_started)
    summary += ", " + std::to_string(stopped.size()) + " stopped, " + std::to_string(not_started) +
               " not started (the same command resumes them)";
  if (!failed.empty()) {
    summary += ", " + std::to_string(failed.size()) + " failed:";
    for (const std::string& f : failed) summary += " " + f;
  }
  std::fprintf(stderr, "%s\n", summary.c_str());
  if (!failed.empty()) return 1;
  if (!stopped.empty() || not_started) return 130;
  return 0;
}

}  // namespace fnet::sim
