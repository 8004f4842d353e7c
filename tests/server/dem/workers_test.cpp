// The thread team of the time steps: every part runs exactly once per call, on distinct threads,
// also after the team has gone to sleep, and a team of one runs everything on the caller.
#include "server/dem/workers.hpp"

#include <chrono>
#include <set>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace fnet::sim {
namespace {

TEST(Workers, EveryPartOncePerCall) {
  for (const unsigned threads : {1u, 2u, 4u}) {
    Workers team(threads);
    std::vector<long> calls(threads, 0);
    for (int k = 0; k < 20000; ++k) team.run([&](unsigned part) { ++calls[part]; });
    for (unsigned part = 0; part < threads; ++part)
      EXPECT_EQ(calls[part], 20000) << threads << " threads, part " << part;
  }
}

TEST(Workers, PartsRunOnDistinctThreadsAndWakeAfterSleeping) {
  Workers team(3);
  for (int round = 0; round < 3; ++round) {
    std::this_thread::sleep_for(std::chrono::milliseconds(150));  // long enough for the team to sleep
    std::vector<std::thread::id> ids(3);
    team.run([&](unsigned part) { ids[part] = std::this_thread::get_id(); });
    EXPECT_EQ(ids[0], std::this_thread::get_id());
    EXPECT_EQ(std::set<std::thread::id>(ids.begin(), ids.end()).size(), 3u) << "round " << round;
  }
}

TEST(Workers, SharesTileTheRange) {
  for (const std::size_t count : {0ul, 1ul, 7ul, 2000ul})
    for (const unsigned parts : {1u, 2u, 3u}) {
      EXPECT_EQ(share_begin(count, 0, parts), 0u);
      EXPECT_EQ(share_begin(count, parts, parts), count);
      for (unsigned p = 0; p < parts; ++p) EXPECT_LE(share_begin(count, p, parts), share_begin(count, p + 1, parts));
    }
}

}  // namespace
}  // namespace fnet::sim
