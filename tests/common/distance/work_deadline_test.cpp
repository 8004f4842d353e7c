// A computation's time budget (work_deadline.hpp): the solvers stop once it is spent, throwing
// WorkDeadlineExceeded soon after; within it, or with none open, they answer exactly as before.
#include "common/distance/work_deadline.hpp"

#include <chrono>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "tests/common/distance/distance_support.hpp"
#include "tests/common/distance/distance_test_util.hpp"

namespace fnet {
namespace {

using Clock = std::chrono::steady_clock;
using Seconds = std::chrono::duration<double>;

struct Pair {
  Diagram a, b;
};

Pair large_pair() {
  std::mt19937_64 rng(29);
  const Diagram a = test::random_diagram(rng, 3000, 1.0, false);
  return {a, test::perturbed(rng, a, 0.01)};
}

TEST(WorkDeadline, EverySolverStopsSoonAfterItsBudgetIsSpent) {
  const Pair p = large_pair();
  for (const double q : {0.0, 1.0, 2.0}) {
    const auto begin = Clock::now();
    const DistanceResult full = test::distance(p.a, p.b, q, EssentialConvention::floor);
    const Seconds unbounded = Clock::now() - begin;
    const double budget = unbounded.count() / 20;
    const auto start = Clock::now();
    try {
      const WorkDeadline deadline{Seconds(budget)};
      test::distance(p.a, p.b, q, EssentialConvention::floor);
      ADD_FAILURE() << "q " << q << ": finished although its budget was a twentieth of " << unbounded.count() << " s";
    } catch (const WorkDeadlineExceeded& e) {
      EXPECT_EQ(e.seconds(), budget);
      // Stopped within its budget and the slack of a few steps, well before the whole computation.
      EXPECT_LT(Seconds(Clock::now() - start).count(), budget + unbounded.count() / 2) << "q " << q;
    }
    EXPECT_GT(full.value, 0);
  }
}

TEST(WorkDeadline, WithinItsBudgetOrWithoutOneTheAnswerIsTheSameBitForBit) {
  const Pair p = large_pair();
  for (const double q : {0.0, 1.0, 2.0}) {
    const DistanceResult free = test::distance(p.a, p.b, q, EssentialConvention::floor);
    const WorkDeadline deadline(Seconds(3600));
    const DistanceResult bounded = test::distance(p.a, p.b, q, EssentialConvention::floor);
    EXPECT_EQ(free.value, bounded.value) << "q " << q;
  }
}

TEST(WorkDeadline, AnInnerDeadlineNeverExtendsTheOuterAndTheOuterComesBack) {
  EXPECT_NO_THROW(check_work_deadline_now());  // none open
  const WorkDeadline outer(Seconds(0));
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  {
    const WorkDeadline inner(Seconds(3600));
    try {
      check_work_deadline_now();
      ADD_FAILURE() << "the inner deadline extended the outer one";
    } catch (const WorkDeadlineExceeded& e) {
      EXPECT_EQ(e.seconds(), 0);
    }
  }
  EXPECT_THROW(check_work_deadline_now(), WorkDeadlineExceeded);
  // The strided check reads the clock once every kCheckStride calls.
  std::uint32_t calls = 0;
  try {
    for (; calls < 10 * kCheckStride; ++calls) check_work_deadline();
  } catch (const WorkDeadlineExceeded&) {
  }
  EXPECT_LE(calls, kCheckStride);
}

TEST(WorkDeadline, AnotherThreadHasNoDeadline) {
  const WorkDeadline deadline(Seconds(0));
  bool threw = false;
  std::thread([&] {
    try {
      for (std::uint32_t k = 0; k < 4 * kCheckStride; ++k) check_work_deadline();
      check_work_deadline_now();
    } catch (const WorkDeadlineExceeded&) {
      threw = true;
    }
  }).join();
  EXPECT_FALSE(threw);
}

}  // namespace
}  // namespace fnet
