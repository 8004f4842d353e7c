// The registry writes each accepted frame's network to the run's store and keeps none in memory:
// a network is read back from the store when asked for, also by a registry that reloaded it. The
// store is written off the registry's lock: a frame is readable as soon as it is committed, and a
// store that fails fails its run until a retry writes what waits.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include <boost/asio/thread_pool.hpp>
#include <gtest/gtest.h>

#include "server/registry/run_registry.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::server {
namespace {

using namespace std::chrono_literals;

RunFrame run_frame(std::uint32_t index, std::size_t lammps) {
  RunFrame f;
  f.header = {"nets", index, 10ull * index, 0.0, 0.8, 3.0};
  f.frame = testing::lammps_frame(lammps);
  f.frame.label = frame_label("nets", index);
  return f;
}

void wait_for(const Registry& r, std::size_t frames) {
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  while (std::chrono::steady_clock::now() < deadline) {
    const auto s = r.run("nets");
    if (s && s->frames >= frames && s->pending == 0) return;
    std::this_thread::sleep_for(10ms);
  }
  FAIL() << "frames not committed";
}

TEST(RegistryNetwork, NetworksGoToTheStoreNotToMemoryAndComeBackAfterAReload) {
  testing::TempDir dir;
  boost::asio::thread_pool pool(2);
  const Frame a = testing::lammps_frame(9), b = testing::lammps_frame(10);
  {
    Registry registry(dir.path(), pool);
    registry.on_frame(run_frame(0, 9));
    registry.on_frame(run_frame(1, 10));
    wait_for(registry, 2);
    for (std::uint32_t k = 0; k < 2; ++k) {
      const auto kept = registry.frame("nets", k);
      ASSERT_TRUE(kept);
      EXPECT_FALSE(kept->network) << "frame " << k << " keeps its network in memory";
    }
    EXPECT_EQ(registry.network("nets", 1).contacts.size(), b.contacts.size());
    EXPECT_THROW(registry.network("nets", 2), NetworkUnavailable);
  }
  Registry reloaded(dir.path(), pool);
  ASSERT_TRUE(reloaded.load().empty());
  const Frame got = reloaded.network("nets", 0);
  ASSERT_EQ(got.contacts.size(), a.contacts.size());
  for (std::size_t n = 0; n < a.contacts.size(); ++n) {
    EXPECT_EQ(got.contacts[n].i, a.contacts[n].i);
    EXPECT_EQ(got.contacts[n].fn, a.contacts[n].fn);
  }
  EXPECT_EQ(got.particles.size(), a.particles.size());
  EXPECT_EQ(got.particles.back().x, a.particles.back().x);
  try {
    reloaded.network("other", 0);
    ADD_FAILURE() << "no such run";
  } catch (const NetworkUnavailable& e) {
    EXPECT_NE(std::string(e.what()).find("run other frame 0"), std::string::npos) << e.what();
  }
}

TEST(RegistryNetwork, EveryCommittedFrameReadsBackAtOnceWhileFramesFlowIn) {
  testing::TempDir dir;
  boost::asio::thread_pool pool(2);
  Registry registry(dir.path(), pool);
  const std::uint32_t n = 12;
  std::atomic<bool> done{false};
  std::atomic<std::size_t> reads{0};
  std::string failure;
  std::thread reader([&] {
    while (!done) {
      for (std::uint32_t k = 0; k < n; ++k) {
        if (!registry.frame("nets", k)) continue;  // not committed yet
        try {
          const Frame got = registry.network("nets", k);
          if (got.contacts.size() != testing::lammps_frame(k % testing::lammps_frame_count()).contacts.size())
            failure = "frame " + std::to_string(k) + " read back with another network";
          ++reads;
        } catch (const std::exception& e) {
          failure = e.what();
        }
      }
    }
  });
  for (std::uint32_t k = 0; k < n; ++k) registry.on_frame(run_frame(k, k % testing::lammps_frame_count()));
  wait_for(registry, n);
  done = true;
  reader.join();
  EXPECT_EQ(failure, "");
  EXPECT_GT(reads.load(), 0u);
  EXPECT_EQ(registry.network("nets", n - 1).contacts.size(),
            testing::lammps_frame((n - 1) % testing::lammps_frame_count()).contacts.size());
}

// A store that cannot be written fails its run: the frames are analyzed but not committed (not
// counted, not served), they wait in flight, the status the publishers read names the fault,
// and once the store can be written a retry commits every one of them, in order.
TEST(RegistryNetwork, AStoreThatCannotBeWrittenFailsItsRunUntilARetryWritesEveryFrame) {
  testing::TempDir dir;
  boost::asio::thread_pool pool(2);
  std::filesystem::create_directories(store_path(dir.path(), "nets"));  // where the file would go
  RegistryLimits limits;
  limits.store_retry = 10ms;
  Registry registry(dir.path(), pool, limits);
  registry.on_frame(run_frame(0, 0));
  registry.on_frame(run_frame(1, 1));
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  auto s = registry.run("nets");
  // The fault is known once the write is tried, after the frames are queued for it.
  while (!(s->pending == 0 && s->unstored == 2 && !s->store_fault.empty()) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(10ms);
    s = registry.run("nets");
  }
  ASSERT_EQ(s->unstored, 2u) << "the frames were not analyzed";
  EXPECT_EQ(s->frames, 0u);
  EXPECT_FALSE(registry.frame("nets", 1));
  EXPECT_EQ(registry.in_flight(), 2u);
  EXPECT_NE(s->store_fault.find("nets.h5"), std::string::npos) << "the fault names the file: " << s->store_fault;
  EXPECT_THROW(registry.network("nets", 1), NetworkUnavailable);
  const std::vector<RunStatus> failing = registry.tend_stores();
  ASSERT_EQ(failing.size(), 1u);
  EXPECT_EQ(failing[0].store_fault, s->store_fault);
  EXPECT_EQ(failing[0].settled_through, 0u);

  std::filesystem::remove(store_path(dir.path(), "nets"));  // the obstacle goes
  std::vector<RunStatus> healed;
  while (registry.run("nets")->frames < 2 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);
    for (RunStatus& r : registry.tend_stores()) healed.push_back(std::move(r));
  }
  s = registry.run("nets");
  EXPECT_EQ(s->frames, 2u);
  EXPECT_EQ(s->unstored, 0u);
  EXPECT_EQ(s->store_fault, "");
  EXPECT_EQ(registry.in_flight(), 0u);
  EXPECT_EQ(registry.network("nets", 1).contacts.size(), testing::lammps_frame(1).contacts.size());
  for (RunStatus& r : registry.tend_stores()) healed.push_back(std::move(r));
  ASSERT_FALSE(healed.empty());
  EXPECT_EQ(healed.back(), (RunStatus{"nets", "", 2, 2, ""}));
}

TEST(RegistryNetwork, AReloadedRunIsReadThenContinued) {
  testing::TempDir dir;
  boost::asio::thread_pool pool(2);
  {
    Registry registry(dir.path(), pool);
    registry.on_frame(run_frame(0, 0));
    registry.on_frame(run_frame(1, 1));
    wait_for(registry, 2);
  }
  Registry reloaded(dir.path(), pool);
  ASSERT_TRUE(reloaded.load().empty());
  EXPECT_EQ(reloaded.network("nets", 1).contacts.size(), testing::lammps_frame(1).contacts.size());
  reloaded.on_frame(run_frame(2, 2));
  wait_for(reloaded, 3);
  for (std::uint32_t k = 0; k < 3; ++k)
    EXPECT_EQ(reloaded.network("nets", k).contacts.size(), testing::lammps_frame(k).contacts.size()) << k;
  Registry again(dir.path(), pool);
  ASSERT_TRUE(again.load().empty());
  EXPECT_EQ(again.run("nets")->frames, 3u);
}

}  // namespace
}  // namespace fnet::server
