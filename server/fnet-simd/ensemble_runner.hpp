// Runs the realizations of an ensemble as child processes: each is fnet-simd itself
// (/proc/self/exe) as a single run, so that it publishes, checkpoints and stops exactly as one.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fnet::sim {

struct Realization {
  std::uint64_t seed = 0;
  std::string run_id;
  std::filesystem::path checkpoint;  // the child's; its state decides fresh, resumed or complete
  std::filesystem::path log;         // the child's stderr, appended
  std::vector<std::string> args;     // the child's arguments (after argv[0]), its --events-fd excepted
  std::size_t frames = 0;            // planned
  std::size_t first_frame = 0;       // frames already done when it starts
  bool resume = false;
  bool complete = false;  // its checkpoint holds the last frame: not run again
};

// The child reports "frame K" (K frames done) on this descriptor, which the parent reads.
inline constexpr int kEventsFd = 3;

// At most `jobs` children at a time, in the order given. Prints one line per state change on
// stderr (started, each frame unless !frame_lines, finished, stopped, failed with its exit code)
// and a summary. Once `stop` is set it starts no more and sends SIGTERM to the running ones,
// which save their checkpoints and exit; it returns when every child has exited, with 0 when
// every realization finished (now or before), 1 when any failed (named in the summary), else 130
// when the stop left some stopped or not started.
int run_ensemble(const std::string& name, const std::vector<Realization>& runs, unsigned jobs, bool frame_lines,
                 const std::atomic<bool>& stop);

}  // namespace fnet::sim
