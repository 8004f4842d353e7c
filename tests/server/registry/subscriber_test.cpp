// The registry's subscribers: each receives every committed point in commit order, after the
// registry's lock is released; one that stops taking points neither delays the others nor holds
// the lock, and is ended once its outbox is full.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include <boost/asio/thread_pool.hpp>
#include <gtest/gtest.h>

#include "server/registry/run_registry.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::server {
namespace {

using namespace std::chrono_literals;

RunFrame run_frame(std::uint32_t index) {
  RunFrame f;
  f.header = {"subs", index, 10ull * index, 0.0, 0.8, 3.0};
  f.frame = testing::lammps_frame(index % 4);
  f.frame.label = frame_label("subs", index);
  return f;
}

// Records the frames it receives.
class Recorder : public Subscriber {
 public:
  bool deliver(std::uint64_t, const SeriesPoint& p) override {
    std::lock_guard lock(mutex_);
    frames_.push_back(p.header.index);
    return true;
  }
  std::vector<std::uint32_t> frames() const {
    std::lock_guard lock(mutex_);
    return frames_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::uint32_t> frames_;
};

// Blocks in its first delivery until released: a reader that stopped reading.
class Stuck : public Subscriber {
 public:
  bool deliver(std::uint64_t, const SeriesPoint&) override {
    ++calls;
    std::unique_lock lock(mutex_);
    entered = true;
    wake_.notify_all();
    wake_.wait(lock, [this] { return released; });
    return true;
  }
  void wait_entered() {
    std::unique_lock lock(mutex_);
    wake_.wait(lock, [this] { return entered; });
  }
  void release() {
    std::lock_guard lock(mutex_);
    released = true;
    wake_.notify_all();
  }
  std::atomic<int> calls{0};

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  bool entered = false, released = false;
};

std::vector<std::uint32_t> upto(std::uint32_t n) {
  std::vector<std::uint32_t> v;
  for (std::uint32_t k = 0; k < n; ++k) v.push_back(k);
  return v;
}

bool eventually(const std::function<bool()>& done) {
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(5ms);
  }
  return true;
}

TEST(RegistrySubscribers, AStuckSubscriberDelaysNoOtherAndHoldsNoLockAndEndsWhenItsOutboxIsFull) {
  testing::TempDir dir;
  boost::asio::thread_pool pool(2);
  RegistryLimits limits;
  limits.max_pending_points = 4;
  Registry registry(dir.path(), pool, limits);
  const auto stuck = std::make_shared<Stuck>();
  const auto before = std::make_shared<Recorder>(), after = std::make_shared<Recorder>();
  registry.subscribe("", std::nullopt, before);
  registry.subscribe("subs", std::nullopt, stuck);
  registry.on_frame(run_frame(0));
  stuck->wait_entered();  // a pool thread is inside its delivery of frame 0, and stays there
  registry.subscribe("subs", std::nullopt, after);
  constexpr std::uint32_t kFrames = 12;
  for (std::uint32_t k = 1; k < kFrames; ++k) registry.on_frame(run_frame(k));
  // Every frame reaches the others, in order, while the stuck one holds its delivery: the
  // registry's lock is free (runs() takes it) and the others' outboxes are delivered apart.
  ASSERT_TRUE(eventually([&] { return before->frames().size() == kFrames && after->frames().size() == kFrames; }))
      << before->frames().size() << " and " << after->frames().size() << " of " << kFrames;
  EXPECT_EQ(before->frames(), upto(kFrames));
  EXPECT_EQ(after->frames(), upto(kFrames));
  ASSERT_TRUE(registry.run("subs"));
  // Its outbox held at most 4 points: the subscription ended (3 subscriptions became 2).
  EXPECT_EQ(registry.subscriptions(), 2u);
  stuck->release();
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(stuck->calls.load(), 1) << "an ended subscription receives nothing more";
}

TEST(RegistrySubscribers, TheBacklogAndTheLivePointsArriveOnceEachInOrder) {
  testing::TempDir dir;
  boost::asio::thread_pool pool(2);
  Registry registry(dir.path(), pool);
  for (std::uint32_t k = 0; k < 5; ++k) registry.on_frame(run_frame(k));
  ASSERT_TRUE(eventually([&] { return registry.run("subs") && registry.run("subs")->frames == 5; }));
  const auto all = std::make_shared<Recorder>(), since = std::make_shared<Recorder>();
  std::thread more([&] {
    for (std::uint32_t k = 5; k < 20; ++k) registry.on_frame(run_frame(k));
  });
  registry.subscribe("subs", std::nullopt, all);
  registry.subscribe("subs", 2u, since);
  more.join();
  ASSERT_TRUE(eventually([&] { return all->frames().size() >= 20 && since->frames().size() >= 17; }));
  EXPECT_EQ(all->frames(), upto(20));
  std::vector<std::uint32_t> tail = upto(20);
  tail.erase(tail.begin(), tail.begin() + 3);
  EXPECT_EQ(since->frames(), tail);
}

}  // namespace
}  // namespace fnet::server
