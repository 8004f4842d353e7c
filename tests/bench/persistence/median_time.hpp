// Timing of a repeatable piece of work: the median over as many runs as fit a budget.
#pragma once

#include <time.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace fnet::bench {

struct Timing {
  double median_ms = 0;
  std::size_t runs = 0;
};

// CPU time of this thread (user + system, so page faults count), not wall time: on a shared
// machine a run that is preempted would otherwise carry other processes' time.
inline double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

// A first run warms caches and the allocator and sizes the repetition; it is the result only
// when it alone exceeds the budget. Otherwise runs are timed in batches of about a millisecond
// (the clock costs microseconds here), and the median batch, divided by its length, is reported:
// robust to the occasional interrupt or cache flush from a neighbour.
template <class Work>
Timing median_time(Work work, double budget_s) {
  const auto timed = [&](std::size_t runs) {
    const double t0 = thread_cpu_ms();
    for (std::size_t r = 0; r < runs; ++r) work();
    return thread_cpu_ms() - t0;
  };
  const double first = timed(1);
  if (first > budget_s * 1e3) return {first, 1};
  const std::size_t batch = std::max<std::size_t>(1, static_cast<std::size_t>(1.0 / std::max(first, 1e-3)));
  const std::size_t batches =
      std::clamp<std::size_t>(static_cast<std::size_t>(budget_s * 1e3 / (first * static_cast<double>(batch))), 3, 301);
  std::vector<double> ms(batches);
  for (double& t : ms) t = timed(batch) / static_cast<double>(batch);
  std::nth_element(ms.begin(), ms.begin() + static_cast<std::ptrdiff_t>(batches / 2), ms.end());
  return {ms[batches / 2], batches * batch};
}

}  // namespace fnet::bench
