// A fixed team of threads for the data-parallel loops of a time step. run(job) calls job(part)
// for every part in [0, size()): part 0 on the calling thread, the others on the team's threads,
// and returns when all are done. A step is tens of microseconds, so the threads spin on an atomic
// generation counter (for a while, then they sleep on it) and the caller spins until the parts are
// done: no lock and no system call per loop while the team is busy.
// Every loop split over the team writes disjoint data, so results do not depend on the team size.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

namespace fnet::sim {

class Workers {
 public:
  explicit Workers(unsigned threads);  // threads >= 1 (1: everything runs on the caller)
  ~Workers();
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;

  unsigned size() const { return static_cast<unsigned>(threads_.size()) + 1; }
  void run(const std::function<void(unsigned part)>& job);
  std::uint64_t runs() const { return runs_; }  // calls of run() so far

 private:
  std::uint64_t runs_ = 0;

  void loop(unsigned part);

  std::vector<std::thread> threads_;
  const std::function<void(unsigned)>* job_ = nullptr;
  std::atomic<std::uint32_t> generation_{0};  // futex-sized: wait() sleeps on it directly
  std::atomic<std::uint32_t> pending_{0};
  std::atomic<std::uint32_t> sleepers_{0};  // threads asleep on generation_: wake only when > 0
  std::atomic<bool> stop_{false};
};

// [begin, end) of part `part` of `parts` over [0, count), in equal shares.
inline std::size_t share_begin(std::size_t count, unsigned part, unsigned parts) { return count * part / parts; }

}  // namespace fnet::sim
