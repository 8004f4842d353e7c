// Each connection's heavy calls: at most `per_connection` handed to the analysis threads at once,
// the rest started in order as those end; another connection's never wait for them.
#include "server/api/heavy_calls.hpp"

#include <functional>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

namespace fnet::server {
namespace {

TEST(HeavyCalls, AConnectionRunsAtMostItsShareAtOnceTheRestInOrderAndOthersDoNotWait) {
  std::vector<std::function<void()>> pool;  // handed over, not yet run
  const auto calls =
      std::make_shared<HeavyCalls>([&](std::function<void()> work) { pool.push_back(std::move(work)); }, 2);
  std::vector<int> ran;
  for (int k = 0; k < 5; ++k) calls->submit(1, [&ran, k] { ran.push_back(k); });
  calls->submit(2, [&ran] { ran.push_back(100); });
  EXPECT_EQ(pool.size(), 3u) << "connection 1's two and connection 2's one";
  EXPECT_EQ(calls->waiting(), 3u);
  while (!pool.empty()) {
    auto work = std::move(pool.front());
    pool.erase(pool.begin());
    work();
    EXPECT_LE(pool.size(), 3u);
  }
  EXPECT_EQ(ran, (std::vector<int>{0, 1, 100, 2, 3, 4}));
  EXPECT_EQ(calls->waiting(), 0u);
}

}  // namespace
}  // namespace fnet::server
