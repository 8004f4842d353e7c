// The registry keeps a committed frame's row in memory and reads its diagrams and network back
// from the run's store through one cache bounded in bytes. The cache never holds more than its
// bound; what the queries answer does not depend on it (a cache of 0 bytes reads every frame from
// the store, bit for bit what the analysis computed); and a run whose store stopped taking writes
// still serves the frames it committed.
#include "server/registry/frame_cache.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <boost/asio/thread_pool.hpp>
#include <gtest/gtest.h>

#include "common/analysis/frame_analysis.hpp"
#include "common/analysis/metric_vocabulary.hpp"
#include "server/api/registry_frames.hpp"
#include "server/query/diagram_query.hpp"
#include "server/query/pair_query.hpp"
#include "server/query/series_query.hpp"
#include "server/registry/run_registry.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::server {
namespace {

using namespace std::chrono_literals;

constexpr std::uint32_t kFrames = 6;

RunFrame cached_run_frame(std::uint32_t index) {
  RunFrame f;
  f.header = {"cached", index, 10ull * index, 0.0, 0.8, 3.0};
  f.frame = testing::lammps_frame(index % testing::lammps_frame_count());
  f.frame.label = frame_label("cached", index);
  return f;
}

void wait_until(const std::function<bool()>& done, const char* what) {
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) FAIL() << "timed out waiting: " << what;
    std::this_thread::sleep_for(10ms);
  }
}

void wait_committed(const Registry& r, std::size_t frames) {
  wait_until(
      [&] {
        const auto s = r.run("cached");
        return s && s->frames >= frames && s->pending == 0 && s->unstored == 0;
      },
      "frames committed");
}

// Bit for bit: every point's birth and death, and the counts.
void expect_same(const FrameDiagramSet& a, const FrameDiagramSet& b, const std::string& what) {
  for (const ForceKind force : {ForceKind::normal, ForceKind::tangential}) {
    EXPECT_EQ(a[force].pd0, b[force].pd0) << what;
    EXPECT_EQ(a[force].pd1, b[force].pd1) << what;
    EXPECT_EQ(a[force].vertices, b[force].vertices) << what;
    EXPECT_EQ(a[force].edges, b[force].edges) << what;
    EXPECT_EQ(a[force].triangles, b[force].triangles) << what;
  }
}

std::shared_ptr<const AnalyzedFrame> sized_frame(std::size_t points) {
  auto f = std::make_shared<AnalyzedFrame>();
  f->diagrams.normal.pd0.assign(points, {1.0, 0.5});
  return f;
}

TEST(FrameCache, NeverHoldsMoreThanItsBoundAndDropsTheLeastRecentlyUsedFirst) {
  const std::size_t bound = 64 << 10;
  FrameCache cache(bound);
  const std::size_t each = held_bytes(*sized_frame(400));  // about 6.5 kB: 9 fit
  for (std::uint32_t k = 0; k < 40; ++k) {
    cache.keep("a", k, sized_frame(400));
    ASSERT_LE(cache.stats().bytes, bound) << "after frame " << k;
    if (k >= 1) {
      ASSERT_TRUE(cache.diagrams("a", 1)) << "the entry used after every insert was dropped at " << k;
    }
  }
  const FrameCacheStats s = cache.stats();
  EXPECT_GE(s.bytes, each * (s.entries)) << "the bytes counted are at least the points held";
  EXPECT_GT(s.entries, 4u);
  EXPECT_LT(s.entries, bound / each + 1);
  EXPECT_FALSE(cache.diagrams("a", 2)) << "the oldest unused entry is dropped first";
  EXPECT_TRUE(cache.diagrams("a", 39));
  // An entry larger than the bound is not kept, and drops nothing.
  const std::size_t entries = cache.stats().entries;
  cache.keep("a", 100, sized_frame(bound / sizeof(PersistencePoint)));
  EXPECT_FALSE(cache.diagrams("a", 100));
  EXPECT_EQ(cache.stats().entries, entries);
  // Networks share the bound.
  Frame net;
  net.particles.resize(1000);
  cache.keep("a", 0, std::make_shared<const Frame>(net));
  EXPECT_TRUE(cache.network("a", 0));
  EXPECT_FALSE(cache.network("a", 1));
  EXPECT_LE(cache.stats().bytes, bound);
  EXPECT_GT(cache.stats().hits, 0u);
  EXPECT_GT(cache.stats().misses, 0u);
  FrameCache none(0);
  none.keep("a", 0, sized_frame(1));
  EXPECT_EQ(none.stats().bytes, 0u);
  EXPECT_FALSE(none.diagrams("a", 0));
}

TEST(FrameCache, AnswersAreTheSameBitForBitWithNoCacheAsWithALargeOne) {
  testing::TempDir small_dir, large_dir;
  boost::asio::thread_pool pool(2);
  RegistryLimits small_limits, large_limits;
  small_limits.cache_bytes = 0;  // every frame read back from the store
  large_limits.cache_bytes = 256u << 20;
  Registry small(small_dir.path(), pool, small_limits), large(large_dir.path(), pool, large_limits);
  for (std::uint32_t k = 0; k < kFrames; ++k) {
    small.on_frame(cached_run_frame(k));
    large.on_frame(cached_run_frame(k));
  }
  wait_committed(small, kFrames);
  wait_committed(large, kFrames);
  const RegistryFrames small_frames(small), large_frames(large);
  for (std::uint32_t k = 0; k < kFrames; ++k) {
    const FrameDiagramSet reference = analyze_frame(testing::lammps_frame(k % testing::lammps_frame_count()));
    const auto from_store = small.frame("cached", k);
    const auto from_cache = large.frame("cached", k);
    ASSERT_TRUE(from_store && from_cache);
    expect_same(from_store->diagrams, reference, "frame " + std::to_string(k) + " read back from the store");
    expect_same(from_cache->diagrams, reference, "frame " + std::to_string(k) + " from the cache");
    EXPECT_TRUE(small.row("cached", k)->diagrams.normal.pd0.empty()) << "a row holds no points";
    for (const int dim : {0, 1})
      for (const ForceKind force : {ForceKind::normal, ForceKind::tangential}) {
        const query::DiagramRequest r{"cached", k, dim, force};
        EXPECT_EQ(query::diagram_query(small_frames, r).points, query::diagram_query(large_frames, r).points);
      }
  }
  EXPECT_EQ(small.cache_stats().bytes, 0u);
  EXPECT_EQ(small.cache_stats().hits, 0u);
  EXPECT_GT(large.cache_stats().hits, 0u);
  EXPECT_LE(large.cache_stats().bytes, large_limits.cache_bytes);
  // A series computed from the diagrams (not stored: the sentinel convention), a stored one, and
  // distances between frames apart.
  for (const char* convention : {"sentinel", "floor"}) {
    query::SeriesRequest r{"cached", {}, {}};
    r.measure.query = {parse_metric("wasserstein1"), 1, ForceKind::normal, parse_essential_convention(convention)};
    const auto a = query::series_query(small_frames, r).values, b = query::series_query(large_frames, r).values;
    ASSERT_EQ(a.value.size(), kFrames);
    EXPECT_EQ(a.first, b.first);
    EXPECT_EQ(a.value, b.value) << convention;
    EXPECT_TRUE(a.value.back().has_value());
  }
  for (std::uint32_t k = 1; k < kFrames; ++k) {
    query::PairRequest r;
    r.run = r.other_run = "cached";
    r.frame = 0;
    r.other_frame = k;
    r.measure = {parse_metric("bottleneck"), 0, ForceKind::tangential, EssentialConvention::floor};
    EXPECT_EQ(query::pair_query(small_frames, r).distance.value, query::pair_query(large_frames, r).distance.value);
  }
}

// A run no longer live (every planned frame settled, or read back from its store) keeps none of
// its diagrams: the predecessor of a frame that comes after all is read back from the store, and
// the distances are those of a run never interrupted.
TEST(FrameCache, ARunNoLongerLiveKeepsNoDiagramsAndMeasuresALateFrameFromItsStore) {
  testing::TempDir whole_dir, finished_dir, reloaded_dir;
  boost::asio::thread_pool pool(2);
  RegistryLimits limits;
  limits.cache_bytes = 0;
  Registry whole(whole_dir.path(), pool, limits);
  for (std::uint32_t k = 0; k < kFrames; ++k) whole.on_frame(cached_run_frame(k));
  wait_committed(whole, kFrames);

  Registry finished(finished_dir.path(), pool, limits);
  RunInfo info;
  info.run_id = "cached";
  info.particles = 2000;
  info.frames = 3;  // planned: frames 3 and on come after the run finished
  finished.on_info(info);
  for (std::uint32_t k = 0; k < 3; ++k) finished.on_frame(cached_run_frame(k));
  wait_committed(finished, 3);
  finished.tend_stores();  // releases the finished run's predecessor
  {
    Registry first(reloaded_dir.path(), pool, limits);
    for (std::uint32_t k = 0; k < 3; ++k) first.on_frame(cached_run_frame(k));
    wait_committed(first, 3);
  }
  Registry reloaded(reloaded_dir.path(), pool, limits);
  ASSERT_TRUE(reloaded.load().empty());
  EXPECT_EQ(finished.cache_stats().misses + reloaded.cache_stats().misses, 0u);
  for (std::uint32_t k = 3; k < kFrames; ++k) {
    finished.on_frame(cached_run_frame(k));
    reloaded.on_frame(cached_run_frame(k));
  }
  wait_committed(finished, kFrames);
  wait_committed(reloaded, kFrames);
  for (const Registry* r : {&finished, &reloaded})
    for (std::uint32_t k = 1; k < kFrames; ++k) {
      const auto got = r->row("cached", k), want = whole.row("cached", k);
      ASSERT_TRUE(got) << k;
      EXPECT_EQ(got->previous, want->previous) << k;
      EXPECT_EQ(got->distances.value, want->distances.value) << "frame " << k;
    }
  // Frame 2, the released predecessor, was read back from each store (by each frame's job that
  // found it released: with no cache, each reads it).
  EXPECT_GE(finished.cache_stats().misses, 1u);
  EXPECT_GE(reloaded.cache_stats().misses, 1u);
  EXPECT_EQ(finished.run("cached")->rejected, 0u);
  EXPECT_EQ(reloaded.run("cached")->rejected, 0u);
}

// A store that takes no more writes (its continuation cannot be made) leaves the frames it
// committed readable: the registry serves them read back from the file, with no cache at all.
TEST(FrameCache, ARunWhoseStoreStoppedTakingWritesServesTheFramesItCommitted) {
  testing::TempDir dir;
  boost::asio::thread_pool pool(2);
  RegistryLimits limits;
  limits.cache_bytes = 0;
  limits.store_idle = 10ms;
  limits.store_retry = 10ms;
  Registry registry(dir.path(), pool, limits);
  registry.on_frame(cached_run_frame(0));
  registry.on_frame(cached_run_frame(1));
  wait_committed(registry, 2);
  wait_until(
      [&] {
        registry.tend_stores();
        return registry.stores_open() == 0;
      },
      "the idle store closed");
  // Continuing the store writes a fresh copy beside it: a directory in its place makes it fail.
  const std::filesystem::path obstacle = store_path(dir.path(), "cached").string() + ".new";
  std::filesystem::create_directories(obstacle);
  std::ofstream(obstacle / "keep") << "x";
  registry.on_frame(cached_run_frame(2));
  wait_until([&] { return !registry.run("cached")->store_fault.empty(); }, "the store fault");
  for (std::uint32_t k = 0; k < 2; ++k) {
    const auto f = registry.frame("cached", k);
    ASSERT_TRUE(f) << k;
    expect_same(f->diagrams, analyze_frame(testing::lammps_frame(k)), "frame " + std::to_string(k));
    EXPECT_EQ(registry.network("cached", k).contacts.size(), testing::lammps_frame(k).contacts.size());
  }
  EXPECT_FALSE(registry.frame("cached", 2)) << "a frame waiting for its store is not committed yet";
  std::filesystem::remove_all(obstacle);
  wait_until(
      [&] {
        registry.tend_stores();
        return registry.run("cached")->frames == 3;
      },
      "the retry");
  const auto f = registry.frame("cached", 2);
  ASSERT_TRUE(f);
  expect_same(f->diagrams, analyze_frame(testing::lammps_frame(2)), "frame 2");
  EXPECT_EQ(registry.cache_stats().bytes, 0u);
}

}  // namespace
}  // namespace fnet::server
