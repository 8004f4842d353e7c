// fnet-server answers from the runs' stores through its cache: two servers read the same run from
// DDS, one with no cache (--cache-mib 0: every diagram and network read back from its store), one
// with the default; every diagram.get, series.get and distance.get answer is the same, bit for
// bit, and server.status counts what each cache held.
#include <string>

#include <gtest/gtest.h>

#include "tests/e2e/line_connection.hpp"
#include "tests/e2e/service_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

constexpr int kCacheDomain = 219;  // CONTRIBUTING.md
constexpr std::size_t kCacheFrames = 11;

// The answer without its timing.
json without_timing(json result) {
  result.erase("seconds");
  return result;
}

TEST(FrameCache, AnswersAreTheSameBitForBitWithNoCacheAsWithTheDefault) {
  testing::TempDir tmp;
  std::vector<int> frames;
  for (std::size_t k = 0; k < kCacheFrames; ++k) frames.push_back(static_cast<int>(k));
  const auto run_dir = lammps_run(tmp.path() / "csv", frames);
  ServerProcess none = e2e::start_server(tmp.path() / "data-none", kCacheDomain, tmp.path() / "none.log",
                                         {"--threads", "1", "--cache-mib", "0"});
  ServerProcess fallback =
      e2e::start_server(tmp.path() / "data-default", kCacheDomain, tmp.path() / "default.log", {"--threads", "1"});
  auto pub = publish(run_dir, "cached", kCacheDomain, tmp.path() / "publish.log");
  ASSERT_EQ(pub->wait(180s), 0);
  wait_for_frames(none.port, "cached", kCacheFrames);
  wait_for_frames(fallback.port, "cached", kCacheFrames);
  LineConnection a(none.port), b(fallback.port);
  const auto same = [&](const std::string& method, const json& params) {
    SCOPED_TRACE(method + " " + params.dump());
    const json x = a.call(method, params), y = b.call(method, params);
    ASSERT_TRUE(x.contains("result")) << x;
    ASSERT_TRUE(y.contains("result")) << y;
    EXPECT_EQ(without_timing(x["result"]).dump(), without_timing(y["result"]).dump());
  };
  for (std::size_t k = 0; k < kCacheFrames; ++k)
    for (const int dim : {0, 1})
      for (const char* force : {"normal", "tangential"}) {
        same("diagram.get", {{"run", "cached"}, {"frame", k}, {"dim", dim}, {"force", force}});
        if (k > 0)
          same("distance.get", {{"run", "cached"},
                                {"frame", 0},
                                {"other_frame", k},
                                {"metric", "wasserstein2"},
                                {"dim", dim},
                                {"force", force}});
      }
  for (const char* essential : {"floor", "sentinel"})
    same("series.get", {{"run", "cached"}, {"metric", "wasserstein1"}, {"essential", essential}});
  same("network.get", {{"run", "cached"}, {"frame", 3}});
  const json no_cache = a.call("server.status", json::object())["result"]["cache"];
  const json with_cache = b.call("server.status", json::object())["result"]["cache"];
  EXPECT_EQ(no_cache["capacity_bytes"], 0);
  EXPECT_EQ(no_cache["bytes"], 0);
  EXPECT_EQ(no_cache["hits"], 0);
  EXPECT_GE(no_cache["misses"].get<std::size_t>(), kCacheFrames) << no_cache;
  EXPECT_EQ(with_cache["capacity_bytes"], 64 << 20);
  EXPECT_GT(with_cache["hits"].get<std::size_t>(), 0u) << with_cache;
  EXPECT_LE(with_cache["bytes"].get<std::size_t>(), std::size_t{64} << 20);
}

}  // namespace
}  // namespace fnet::e2e
