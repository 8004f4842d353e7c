#include "server/registry/store_check.hpp"

#include <poll.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <deque>
#include <list>
#include <optional>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>

#include "server/registry/child_process.hpp"

namespace fnet::server {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kAnswerKept = 2048;  // of a check's answer: the reason, and no more
constexpr std::size_t kBatch = 16;         // files one child checks at most

std::string seconds_text(double s) {
  std::ostringstream out;
  out << s;
  return out.str();
}

// The reason a check gives for its store: its output on one line, naming the file.
std::string reason(const std::string& file, std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  if (text.find(file) == std::string::npos && !text.empty()) text = file + ": " + text;
  return text;
}

// What a check that ended says of its store: empty when it passed.
std::string refusal(const std::string& file, int status, const std::string& output) {
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  const std::string said = reason(file, output);
  if (WIFSIGNALED(status))
    return file + ": its check ended by signal " + std::to_string(WTERMSIG(status)) + " (" +
           strsignal(WTERMSIG(status)) + ")" + (said.empty() ? "" : ": " + said);
  return said.empty() ? file + ": its check failed (exit code " + std::to_string(WEXITSTATUS(status)) + ")" : said;
}

}  // namespace

bool StoreChecker::Identity::operator==(const Identity& o) const {
  return device == o.device && inode == o.inode && size == o.size && modified.tv_sec == o.modified.tv_sec &&
         modified.tv_nsec == o.modified.tv_nsec;
}

std::optional<StoreChecker::Identity> StoreChecker::identity(const std::filesystem::path& file) {
  struct stat s {};
  if (stat(file.c_str(), &s) != 0 || !S_ISREG(s.st_mode)) return std::nullopt;
  return Identity{s.st_dev, s.st_ino, s.st_size, s.st_mtim};
}

std::vector<std::string> StoreChecker::refusals(const std::vector<std::filesystem::path>& files) {
  std::vector<std::string> out(files.size());
  std::vector<std::optional<Identity>> before(files.size());
  std::vector<std::size_t> which;
  {
    std::lock_guard lock(mutex_);
    for (std::size_t k = 0; k < files.size(); ++k) {
      before[k] = identity(files[k]);
      if (!before[k]) continue;
      const auto it = verdicts_.find(files[k]);
      if (it != verdicts_.end() && it->second.identity == *before[k])
        out[k] = it->second.refusal;
      else
        which.push_back(k);
    }
  }
  check(files, which, out);
  std::lock_guard lock(mutex_);
  for (const std::size_t k : which) {
    const std::optional<Identity> after = identity(files[k]);
    if (after && *after == *before[k]) {
      verdicts_[files[k]] = {*after, out[k]};
    } else {
      verdicts_.erase(files[k]);
      out[k] = files[k].string() + ": it changed while it was checked (a store is read once its writer has finished)";
    }
  }
  return out;
}

void StoreChecker::check(const std::vector<std::filesystem::path>& files, const std::vector<std::size_t>& which,
                         std::vector<std::string>& out) const {
  // A child checks a batch of files in turn, answering each on a line of its own; each file has
  // the whole deadline from the answer before it. A child that crashes or overruns refuses the
  // file it was at, and the rest of its batch is checked again by another.
  struct Running {
    std::vector<std::size_t> batch;  // indices of `files`, in the order given
    std::size_t answered = 0;
    ChildProcess child;
    Clock::time_point deadline;  // for batch[answered]
    std::string line;            // the answer being read, at most kAnswerKept bytes of it
  };
  const auto allowed = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options_.seconds));
  const std::size_t parallel = std::max(1u, options_.parallel);
  std::deque<std::size_t> waiting(which.begin(), which.end());
  std::list<Running> running;
  const auto take_answers = [&](Running& r, const std::string& text) {
    for (const char c : text) {
      if (c != '\n') {
        if (r.line.size() < kAnswerKept) r.line += c;
        continue;
      }
      if (r.answered < r.batch.size()) {
        const std::string file = files[r.batch[r.answered++]].string();
        const std::string said = reason(file, r.line);
        out[r.batch[r.answered - 1]] = r.line == kStorePassed ? ""
                                       : said.empty()         ? file + ": its check refused it without a reason"
                                                              : said;
      }
      r.line.clear();
      r.deadline = Clock::now() + allowed;
    }
  };
  // The files of a child that ended or was killed: `why` for the one it was at, the rest waiting again.
  const auto give_back = [&](Running& r, const std::string& why) {
    if (r.answered >= r.batch.size()) return;
    out[r.batch[r.answered]] = why;
    waiting.insert(waiting.begin(), r.batch.begin() + static_cast<std::ptrdiff_t>(r.answered) + 1, r.batch.end());
  };
  while (!waiting.empty() || !running.empty()) {
    while (running.size() < parallel && !waiting.empty()) {
      // The files spread over the children that may run at once, a bounded batch each.
      const std::size_t n = std::clamp<std::size_t>((waiting.size() + parallel - 1) / parallel, 1, kBatch);
      std::vector<std::size_t> batch(waiting.begin(), waiting.begin() + static_cast<std::ptrdiff_t>(n));
      waiting.erase(waiting.begin(), waiting.begin() + static_cast<std::ptrdiff_t>(n));
      std::vector<std::string> argv = options_.command;
      for (const std::size_t k : batch) argv.push_back(files[k].string());
      try {
        running.push_back({batch, 0, ChildProcess(argv.front(), argv), Clock::now() + allowed, {}});
      } catch (const std::exception& e) {
        for (const std::size_t k : batch) out[k] = files[k].string() + ": its check did not start: " + e.what();
      }
    }
    // Wait for output, an exit or the first deadline. A child that closed its output without
    // exiting (yet) is looked at again shortly.
    std::vector<pollfd> fds;
    auto wake = Clock::time_point::max();
    for (const Running& r : running) {
      if (r.child.output() >= 0)
        fds.push_back({r.child.output(), POLLIN, 0});
      else
        wake = std::min(wake, Clock::now() + std::chrono::milliseconds(10));
      wake = std::min(wake, r.deadline);
    }
    if (running.empty()) continue;
    const auto wait = std::chrono::ceil<std::chrono::milliseconds>(wake - Clock::now()).count();
    poll(fds.data(), fds.size(), static_cast<int>(std::clamp<long long>(wait, 0, 1000)));
    for (auto r = running.begin(); r != running.end();) {
      take_answers(*r, r->child.read_output());
      if (const std::optional<int> status = r->child.exited()) {
        for (std::string rest; !(rest = r->child.read_output()).empty();) take_answers(*r, rest);
        if (r->answered < r->batch.size()) {
          const std::string file = files[r->batch[r->answered]].string();
          const std::string why = refusal(file, *status, r->line);
          give_back(*r, why.empty() ? file + ": its check ended without an answer" : why);
        }
      } else if (Clock::now() >= r->deadline) {
        r->child.kill();
        give_back(*r, files[r->batch[r->answered]].string() + ": its check did not finish within " +
                          seconds_text(options_.seconds) +
                          " s (--store-check-seconds): HDF5 may loop forever on a damaged file");
      } else {
        ++r;
        continue;
      }
      r = running.erase(r);
    }
  }
}

}  // namespace fnet::server
