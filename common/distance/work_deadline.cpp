#include "common/distance/work_deadline.hpp"

#include <sstream>

namespace fnet {

WorkDeadlineExceeded::WorkDeadlineExceeded(double seconds)
    : std::runtime_error([seconds] {
        std::ostringstream out;
        out << "the computation took longer than its budget of " << seconds << " s";
        return out.str();
      }()),
      seconds_(seconds) {}

WorkDeadline::WorkDeadline(std::chrono::duration<double> budget) : outer_(current_) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::nanoseconds>(budget);
  // An inner deadline never extends the outer one.
  current_ = State{outer_ && outer_->until < until ? outer_->until : until,
                   outer_ && outer_->until < until ? outer_->seconds : budget.count()};
  since_clock_ = 0;
}

WorkDeadline::~WorkDeadline() { current_ = outer_; }

void check_work_deadline_now() {
  const auto& state = WorkDeadline::current_;
  if (state && std::chrono::steady_clock::now() > state->until) throw WorkDeadlineExceeded(state->seconds);
}

}  // namespace fnet
