// The registry's subscribers: each receives every committed point in commit order, after the
// registry's lock is released; one that stops taking points neither delays the others nor holds
// the lock, and is ended once its outbox is full.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
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

TEST(RegistrySubscribers, AStuckSubscriberDelaysNoOtherHoldsNoLockAndGetsTheRestOnceFree) {
  testing::TempDir dir;
  boost::asio::thread_pool pool(2);
  Registry registry(dir.path(), pool);
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
  // registry's lock is free (runs() takes it) and the others' deliveries go on apart.
  ASSERT_TRUE(eventually([&] { return before->frames().size() == kFrames && after->frames().size() == kFrames; }))
      << before->frames().size() << " and " << after->frames().size() << " of " << kFrames;
  EXPECT_EQ(before->frames(), upto(kFrames));
  EXPECT_EQ(after->frames(), upto(kFrames));
  ASSERT_TRUE(registry.run("subs"));
  EXPECT_EQ(registry.subscriptions(), 3u);
  stuck->release();
  // Nothing was copied for it meanwhile: the rest is read from the committed frames, in order.
  ASSERT_TRUE(eventually([&] { return stuck->calls.load() == static_cast<int>(kFrames); })) << stuck->calls.load();
}

// Takes points only while the test has given it room; asks to be resumed otherwise.
class Paced : public Subscriber {
 public:
  bool ready(const std::function<void()>& resume) override {
    std::lock_guard lock(mutex_);
    if (room_ > 0) return true;
    resume_ = resume;
    return false;
  }
  bool deliver(std::uint64_t, const SeriesPoint& p) override {
    std::lock_guard lock(mutex_);
    frames_.push_back(p.header.index);
    if (room_ > 0) --room_;
    return true;
  }
  // Gives room for `n` more points, then resumes the delivery.
  void give(int n) {
    std::function<void()> resume;
    {
      std::lock_guard lock(mutex_);
      room_ += n;
      resume.swap(resume_);
    }
    if (resume) resume();
  }
  std::vector<std::uint32_t> frames() const {
    std::lock_guard lock(mutex_);
    return frames_;
  }

 private:
  mutable std::mutex mutex_;
  int room_ = 0;
  std::function<void()> resume_;
  std::vector<std::uint32_t> frames_;
};

TEST(RegistrySubscribers, ASubscriberWithoutRoomGetsNothingUntilItHasThenEveryPointInOrder) {
  testing::TempDir dir;
  boost::asio::thread_pool pool(2);
  Registry registry(dir.path(), pool);
  constexpr std::uint32_t kFrames = 300;
  for (std::uint32_t k = 0; k < kFrames; ++k) registry.on_frame(run_frame(k));
  ASSERT_TRUE(eventually([&] { return registry.run("subs") && registry.run("subs")->frames == kFrames; }));
  const auto paced = std::make_shared<Paced>();
  registry.subscribe("subs", std::nullopt, paced);
  std::this_thread::sleep_for(100ms);
  EXPECT_TRUE(paced->frames().empty()) << "points were sent to a subscriber without room";
  paced->give(10);  // room for ten points: it is asked before each
  ASSERT_TRUE(eventually([&] { return paced->frames().size() >= 10; }));
  std::this_thread::sleep_for(100ms);
  EXPECT_EQ(paced->frames().size(), 10u);
  while (paced->frames().size() < kFrames) {
    const std::size_t had = paced->frames().size();
    paced->give(50);
    ASSERT_TRUE(eventually([&] { return paced->frames().size() > had; })) << "the delivery did not resume at " << had;
  }
  EXPECT_EQ(paced->frames(), upto(kFrames));
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
