#include "server/sources/lammps_follow.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>
#include <thread>
#include <utility>

#include <boost/program_options.hpp>

namespace fnet::sources {

namespace {

using Clock = std::chrono::steady_clock;

bool compressed(const std::string& pattern) {
  return pattern.size() >= 3 && pattern.compare(pattern.size() - 3, 3, ".gz") == 0;
}

// One kind of dump: its files as they appear, and its whole snapshots not yet paired, by TIMESTEP.
class FollowedDumps {
 public:
  FollowedDumps(std::string pattern, DumpKind kind) : pattern_(std::move(pattern)), kind_(kind) {}

  // Reads what was completed since the last call; true when a snapshot was.
  bool poll() {
    bool any = false;
    pending_ = false;
    for (const std::filesystem::path& file : dump_files_now(pattern_)) {
      auto it = tails_.find(file);
      if (it == tails_.end()) it = tails_.emplace(file, DumpTail(file, kind_)).first;
      for (DumpSnapshot& s : it->second.read_new()) {
        if (s.timestep <= last_ && taken_any_)
          throw std::runtime_error(s.where() + ": TIMESTEP " + std::to_string(s.timestep) + " after TIMESTEP " +
                                   std::to_string(last_) + " was read");
        const std::string where = s.where();
        const auto [at, inserted] = whole_.emplace(s.timestep, std::move(s));
        if (!inserted)
          throw std::runtime_error(where + ": TIMESTEP " + std::to_string(at->first) + " again (first at " +
                                   at->second.where() + ")");
        any = true;
      }
      pending_ = pending_ || it->second.pending();
    }
    return any;
  }

  // Whether a file held more than whole snapshots at the last poll: one being written.
  bool pending() const { return pending_; }
  bool empty() const { return whole_.empty(); }
  const DumpSnapshot& first() const { return whole_.begin()->second; }
  DumpSnapshot take() {
    DumpSnapshot s = std::move(whole_.begin()->second);
    whole_.erase(whole_.begin());
    last_ = s.timestep;
    taken_any_ = true;
    return s;
  }
  // Once the writer is done: a file's rest that is not a whole snapshot throws.
  void require_read() const {
    for (const auto& [file, tail] : tails_) tail.require_read();
  }

 private:
  std::string pattern_;
  DumpKind kind_;
  std::map<std::filesystem::path, DumpTail> tails_;
  std::map<std::uint64_t, DumpSnapshot> whole_;
  std::uint64_t last_ = 0;
  bool taken_any_ = false, pending_ = false;
};

// Whether LAMMPS's log says the run finished: LAMMPS writes "Total wall time" as it exits.
class RunLog {
 public:
  explicit RunLog(std::string path) : path_(std::move(path)) {}
  bool finished() {
    if (path_.empty()) return false;
    std::ifstream in(path_);
    if (!in) return false;
    in.seekg(static_cast<std::streamoff>(read_));
    std::string line;
    while (std::getline(in, line)) {
      if (in.eof()) break;  // a line not yet ended is read again, whole, at the next call
      read_ += line.size() + 1;
      if (line.rfind("Total wall time", 0) == 0) return true;
    }
    return false;
  }

 private:
  std::string path_;
  std::uint64_t read_ = 0;
};

class LammpsFollow final : public FrameSource {
 public:
  LammpsFollow(LammpsOptions options, FollowOptions follow)
      : options_(std::move(options)),
        follow_(std::move(follow)),
        atoms_(options_.atoms, DumpKind::atoms),
        pairs_(options_.pairs, DumpKind::entries),
        log_(follow_.log),
        progress_(Clock::now()) {
    first_ = take();
    if (first_) info_.particles = static_cast<std::uint32_t>(grains_->ids.size());
    info_.config_json = lammps_config(options_, dimension_, region_);
  }
  const RunInfo& announcement() const override { return info_; }
  std::optional<RunFrame> next() override {
    if (first_) return std::exchange(first_, std::nullopt);
    return take();
  }

 private:
  std::optional<RunFrame> take() {
    if (done_) return std::nullopt;
    while (true) {
      const bool ended = ended_;
      const bool read = atoms_.poll() | pairs_.poll();
      if (read) progress_ = Clock::now();
      if (std::optional<RunFrame> frame = paired(ended)) return frame;
      if (ended) break;
      // The log is read after the dumps were: a run it says finished wrote them all before.
      if (log_.finished() || Clock::now() - progress_ > follow_.idle_timeout)
        ended_ = true;
      else
        std::this_thread::sleep_for(follow_.poll);
    }
    done_ = true;
    atoms_.require_read();
    pairs_.require_read();
    if (!atoms_.empty()) lone(atoms_.first(), "pair", options_.pairs);
    if (!pairs_.empty()) lone(pairs_.first(), "per-atom", options_.atoms);
    return std::nullopt;
  }

  // The frame of the earliest TIMESTEP whole in both kinds. A snapshot whose partner is missing
  // while the other kind is past it and holds nothing half-written is an error; so is any at the end.
  std::optional<RunFrame> paired(bool ended) {
    while (!atoms_.empty() && !pairs_.empty()) {
      const std::uint64_t a = atoms_.first().timestep, p = pairs_.first().timestep;
      if (a == p) return frame(atoms_.take(), pairs_.take());
      if (a < p && (ended || !pairs_.pending())) lone(atoms_.first(), "pair", options_.pairs);
      if (p < a && (ended || !atoms_.pending())) lone(pairs_.first(), "per-atom", options_.atoms);
      return std::nullopt;
    }
    return std::nullopt;
  }

  [[noreturn]] static void lone(const DumpSnapshot& s, const char* other, const std::string& pattern) {
    throw std::runtime_error(s.where() + ": TIMESTEP " + std::to_string(s.timestep) + " has no snapshot in the " +
                             other + " dumps " + pattern);
  }

  RunFrame frame(const DumpSnapshot& atoms, const DumpSnapshot& pairs) {
    if (!grains_) {
      grains_ = grain_ids(atoms, options_.wall_types);
      dimension_ = run_dimension(options_, atoms);
    }
    LammpsFrame f = checked_frame(atoms, pairs, *grains_, dimension_, options_, index_++);
    region_ = f.region;
    return std::move(f.run);
  }

  LammpsOptions options_;
  FollowOptions follow_;
  FollowedDumps atoms_, pairs_;
  RunLog log_;
  Clock::time_point progress_;  // when a snapshot was last completed
  bool ended_ = false, done_ = false;
  std::optional<GrainIds> grains_;
  RunDimension dimension_;
  std::uint32_t index_ = 0;
  DensityRegion region_ = DensityRegion::box;
  RunInfo info_;
  std::optional<RunFrame> first_;  // read to announce the run, until taken
};

double seconds_of(const std::string& flag, const std::string& text) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !(value > 0) || !std::isfinite(value))
    throw boost::program_options::error(flag + ": \"" + text + "\" is not a positive number of seconds");
  return value;
}

}  // namespace

FollowOptions follow_options(const SourceArguments& given) {
  FollowOptions out;
  if (const std::string t = flag_value(given, "idle-timeout"); !t.empty())
    out.idle_timeout = std::chrono::duration<double>(seconds_of("--idle-timeout", t));
  out.log = flag_value(given, "lammps-log");
  return out;
}

std::unique_ptr<FrameSource> follow_lammps(const LammpsOptions& options, const FollowOptions& follow) {
  for (const std::string& pattern : {options.atoms, options.pairs})
    if (compressed(pattern))
      throw boost::program_options::error("--follow reads plain-text dumps, not " + pattern +
                                          " (a gzip stream is whole only once closed)");
  return std::make_unique<LammpsFollow>(options, follow);
}

}  // namespace fnet::sources
