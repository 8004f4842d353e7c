// A time budget for one computation on one thread. A caller that answers someone who may ask for
// too much (fnet-server's heavy API calls) opens a WorkDeadline around the computation; the long
// loops of the solvers call check_work_deadline() between steps, which throws WorkDeadlineExceeded
// once the budget is spent. Without a WorkDeadline open on the thread (the frames' own analysis,
// the offline tools) the check never throws. The clock is read once every kCheckStride checks, so
// a check costs an increment and a branch.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>

namespace fnet {

class WorkDeadlineExceeded : public std::runtime_error {
 public:
  explicit WorkDeadlineExceeded(double seconds);
  double seconds() const { return seconds_; }  // the budget that was spent

 private:
  double seconds_;
};

// Open for its lifetime on the thread that made it; nested deadlines restore the outer one.
class WorkDeadline {
 public:
  explicit WorkDeadline(std::chrono::duration<double> budget);
  ~WorkDeadline();
  WorkDeadline(const WorkDeadline&) = delete;
  WorkDeadline& operator=(const WorkDeadline&) = delete;

 private:
  struct State {
    std::chrono::steady_clock::time_point until;
    double seconds = 0;
  };
  std::optional<State> outer_;
  friend void check_work_deadline();
  friend void check_work_deadline_now();
  static inline thread_local std::optional<State> current_;
  static inline thread_local std::uint32_t since_clock_ = 0;
};

inline constexpr std::uint32_t kCheckStride = 1024;

// Throws WorkDeadlineExceeded when the thread's deadline has passed, reading the clock now: for
// steps that each take long.
void check_work_deadline_now();

// The same, reading the clock once every kCheckStride calls: for the steps of a solver's loops.
inline void check_work_deadline() {
  if (!WorkDeadline::current_ || ++WorkDeadline::since_clock_ < kCheckStride) return;
  WorkDeadline::since_clock_ = 0;
  check_work_deadline_now();
}

}  // namespace fnet
