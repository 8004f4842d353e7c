// The registry writes each accepted frame's network to the run's store and keeps none in memory:
// a network is read back from the store when asked for, also by a registry that reloaded it.
#include <chrono>
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

}  // namespace
}  // namespace fnet::server
