// The pool's scheduler on a real thread pool: a queue with jobs waiting and none running goes
// before a queue that has had its turn, so one queue's backlog never makes another wait for all of
// it; a queue alone uses every thread; jobs posted by jobs run, a job that throws stops nothing.
#include "server/registry/fair_scheduler.hpp"

#include <algorithm>
#include <chrono>
#include <future>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <boost/asio/thread_pool.hpp>
#include <gtest/gtest.h>

namespace fnet::server {
namespace {

using namespace std::chrono_literals;

// The names of the jobs in the order they started.
class StartOrder {
 public:
  FairScheduler::Job job(const std::string& name) {
    return [this, name] {
      std::lock_guard lock(mutex_);
      names_.push_back(name);
    };
  }
  std::vector<std::string> names() const {
    std::lock_guard lock(mutex_);
    return names_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::string> names_;
};

// A job that holds its thread until released, and says when it started.
struct Gate {
  std::promise<void> started, release;
  FairScheduler::Job job() {
    return [this] {
      started.set_value();
      release.get_future().wait();
    };
  }
};

// Posts the gate's job to `queue` and waits until it holds a thread.
void hold(FairScheduler& scheduler, const std::string& queue, Gate& gate) {
  scheduler.post(queue, gate.job());
  ASSERT_EQ(gate.started.get_future().wait_for(10s), std::future_status::ready);
}

// One thread, held by a job of queue `holder` until release() is called.
class FairSchedulerOnOneThread : public ::testing::Test {
 protected:
  void hold_by(const std::string& holder) { hold(scheduler, holder, gate); }
  void release() {
    gate.release.set_value();
    scheduler.wait_idle();
    pool.join();
  }
  boost::asio::thread_pool pool{1};
  FairScheduler scheduler{pool, 1};
  StartOrder order;
  Gate gate;
};

TEST_F(FairSchedulerOnOneThread, AnotherQueuesJobGoesBeforeTheBacklogOfTheQueueThatRan) {
  hold_by("heavy");
  for (int k = 0; k < 4; ++k) scheduler.post("heavy", order.job("heavy " + std::to_string(k)));
  scheduler.post("ordinary", order.job("ordinary"));
  EXPECT_EQ(scheduler.waiting(), (std::map<std::string, std::size_t>{{"heavy", 4}, {"ordinary", 1}}));
  release();
  // First in, first out would start the ordinary job last.
  EXPECT_EQ(order.names(), (std::vector<std::string>{"ordinary", "heavy 0", "heavy 1", "heavy 2", "heavy 3"}));
  EXPECT_TRUE(scheduler.waiting().empty());
}

TEST_F(FairSchedulerOnOneThread, QueuesWithJobsWaitingTakeTurnsOneJobEach) {
  hold_by("c");
  for (int k = 0; k < 3; ++k) scheduler.post("a", order.job("a" + std::to_string(k)));
  for (int k = 0; k < 2; ++k) scheduler.post("b", order.job("b" + std::to_string(k)));
  scheduler.post("c", order.job("c0"));
  release();
  // a and b have not started a job yet (a first by name), c has; then each in turn, least recently served first.
  EXPECT_EQ(order.names(), (std::vector<std::string>{"a0", "b0", "c0", "a1", "b1", "a2"}));
}

TEST(FairScheduler, AQueueHoldingEveryThreadLetsAnotherQueueTakeTheFirstThreadFreed) {
  boost::asio::thread_pool pool(2);
  FairScheduler scheduler(pool, 2);
  StartOrder order;
  Gate first, second;
  // A queue alone runs on both threads at once.
  hold(scheduler, "heavy", first);
  hold(scheduler, "heavy", second);
  for (int k = 0; k < 3; ++k) scheduler.post("heavy", order.job("heavy " + std::to_string(k)));
  scheduler.post("ordinary", order.job("ordinary"));
  first.release.set_value();
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (order.names().empty() && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(1ms);
  second.release.set_value();
  scheduler.wait_idle();
  pool.join();
  ASSERT_EQ(order.names().size(), 4u);
  EXPECT_EQ(order.names().front(), "ordinary");
}

TEST(FairScheduler, JobsPostedByJobsRunAndAJobThatThrowsStopsNothing) {
  boost::asio::thread_pool pool(2);
  FairScheduler scheduler(pool, 2);
  StartOrder order;
  scheduler.post("a", [] { throw std::runtime_error("planted failure"); });
  scheduler.post("a", [&] { scheduler.post("b", order.job("posted by a job")); });
  scheduler.post("a", order.job("after the failure"));
  scheduler.wait_idle();
  pool.join();
  auto names = order.names();
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"after the failure", "posted by a job"}));
}

}  // namespace
}  // namespace fnet::server
