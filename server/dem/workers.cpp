#include "server/dem/workers.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace fnet::sim {
namespace {

// About 10-30 µs of pausing before a team thread sleeps (longer serial stretches, such as a list
// rebuild, then cost one wake-up); every kYieldEvery pauses the spinner also yields, so that a team
// larger than the free cores still makes progress.
constexpr int kSpins = 1 << 12;
constexpr int kYieldEvery = 1 << 8;

inline void pause(int k) {
  if ((k + 1) % kYieldEvery == 0) {
    std::this_thread::yield();
    return;
  }
#if defined(__x86_64__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

}  // namespace

Workers::Workers(unsigned threads) {
  for (unsigned part = 1; part < threads; ++part) threads_.emplace_back([this, part] { loop(part); });
}

Workers::~Workers() {
  stop_.store(true);
  generation_.fetch_add(1);
  generation_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void Workers::run(const std::function<void(unsigned)>& job) {
  ++runs_;
  if (threads_.empty()) {
    job(0);
    return;
  }
  job_ = &job;
  pending_.store(static_cast<std::uint32_t>(threads_.size()));
  // Sequentially consistent: either a thread about to sleep sees the new generation, or this
  // sees it counted among the sleepers and wakes it.
  generation_.fetch_add(1);
  if (sleepers_.load() > 0) generation_.notify_all();
  job(0);
  for (int k = 0; pending_.load(std::memory_order_acquire) != 0; ++k) pause(k);
}

void Workers::loop(unsigned part) {
  std::uint32_t seen = 0;
  for (;;) {
    int k = 0;
    for (; generation_.load(std::memory_order_acquire) == seen && k < kSpins; ++k) pause(k);
    if (generation_.load() == seen) {
      sleepers_.fetch_add(1);
      while (generation_.load() == seen) generation_.wait(seen);
      sleepers_.fetch_sub(1);
    }
    seen = generation_.load(std::memory_order_acquire);
    if (stop_.load()) return;
    (*job_)(part);
    pending_.fetch_sub(1, std::memory_order_release);
  }
}

}  // namespace fnet::sim
