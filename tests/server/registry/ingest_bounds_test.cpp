// The ingest's back-pressure in bytes, over real DDS on loopback into a registry with real
// stores: while the analysis is held, it takes frames until those held reach
// max_in_flight_bytes (the frame that reaches it is the last), far fewer than max_in_flight;
// once the analysis goes on, every frame is committed.
#include <chrono>
#include <future>
#include <thread>

#include <boost/asio/thread_pool.hpp>
#include <gtest/gtest.h>

#include "common/run/frame_bounds.hpp"
#include "server/registry/ingest.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::server {
namespace {

using namespace std::chrono_literals;

RunFrame frame_of_run(std::uint32_t index) {
  RunFrame f;
  f.header = {"bytes", index, 100ull * index, 0.1 * index, 0.85, 4.0};
  f.frame = testing::lammps_frame(10);
  f.frame.label = frame_label("bytes", index);
  return f;
}

template <class Predicate>
bool eventually(Predicate done, std::chrono::seconds limit = 30s) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(10ms);
  }
  return true;
}

TEST(IngestBounds, FramesAreTakenUntilTheyHoldTheByteBoundAndAllAreCommittedOnceAnalysisGoesOn) {
  constexpr dds_domainid_t kDomain = 216;
  constexpr std::uint32_t kFrames = 6;
  const std::size_t one = frame_bytes(frame_of_run(0).frame.particle_count, frame_of_run(0).frame.contacts.size());
  testing::TempDir dir;
  boost::asio::thread_pool pool(1);
  FairScheduler scheduler(pool, 1);
  Registry registry(dir.path(), scheduler);
  // The one analysis thread held until released.
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  scheduler.post("holder", [released] { released.wait(); });

  const IngestOptions options{kDomain, 64, 2 * one + one / 2, 4 * one};
  EXPECT_EQ(reader_frames(options), 1u);  // the DDS reader holds one largest frame more
  Ingest ingest(registry, options);
  std::thread writer([&] {
    dds::FramePublisher p(kDomain);
    while (p.matched_readers() == 0) std::this_thread::sleep_for(20ms);
    for (std::uint32_t k = 0; k < kFrames; ++k) p.publish(frame_of_run(k));
    p.wait_for_acks(DDS_SECS(60));
  });
  ASSERT_TRUE(eventually([&] { return registry.in_flight() == 3; })) << registry.in_flight() << " frames in flight";
  std::this_thread::sleep_for(500ms);  // time to take more, were the bound not kept
  EXPECT_EQ(registry.in_flight(), 3u);
  EXPECT_EQ(registry.in_flight_bytes(), 3 * one);

  release.set_value();
  EXPECT_TRUE(eventually([&] {
    const auto run = registry.run("bytes");
    return run && run->frames == kFrames;
  }));
  writer.join();
  ingest.stop();
  EXPECT_EQ(registry.in_flight_bytes(), 0u);
  scheduler.wait_idle();
  pool.join();
}

}  // namespace
}  // namespace fnet::server
