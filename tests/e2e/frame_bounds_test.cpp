// What fnet-server accepts from DDS, as a real process fed by a real publisher (this process) on
// loopback: frames out of bounds (header out of range, too large, too many contacts per grain)
// are rejected in their run with a reason naming the frame and the bound, and the run goes on;
// a bad announcement is refused with its reason; stores written before headers were checked
// still give their ensemble's curve; and one run's heavy frames do not keep another run waiting.
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "client/rpc/rpc_client.hpp"
#include "common/analysis/frame_analysis.hpp"
#include "common/store/analysis_store.hpp"
#include "common/transport/frame_transport.hpp"
#include "tests/e2e/service_process.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace std::chrono_literals;

// A publisher in this process, on the loopback configuration the servers use.
dds::FramePublisher publisher(int domain) {
  for (const auto& [name, value] : dds_environment()) setenv(name.c_str(), value.c_str(), 1);
  return dds::FramePublisher(static_cast<dds_domainid_t>(domain));
}

void wait_for_reader(const dds::FramePublisher& p) {
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (p.matched_readers() == 0 && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(50ms);
  ASSERT_GT(p.matched_readers(), 0u) << "fnet-server's reader never matched";
}

RunInfo announcement(const std::string& run, const std::string& ensemble, std::uint32_t frames) {
  RunInfo info;
  info.run_id = run;
  info.particles = 2000;
  info.frames = frames;
  info.config_json = "{}";
  info.ensemble = ensemble;
  return info;
}

// Frame k of the LAMMPS reference run, as frame `index` of `run`.
RunFrame lammps_run_frame(const std::string& run, std::uint32_t index, std::size_t k) {
  RunFrame f;
  f.header = {run, index, 1000ull * index, 0.1 * index, 0.8 + 0.001 * index, 3.0};
  f.frame = testing::lammps_frame(k);
  f.frame.label = frame_label(run, index);
  return f;
}

// `groups` groups of `grains` grains, every pair of a group in contact, with forces drawn from
// `seed`: grains - 1 contacts per grain.
Frame cliques(std::size_t grains, std::size_t groups, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::exponential_distribution<double> force(1.0);
  Frame f;
  f.particle_count = grains * groups;
  for (std::size_t g = 0; g < groups; ++g)
    for (std::size_t i = 0; i < grains; ++i)
      for (std::size_t j = i + 1; j < grains; ++j)
        f.contacts.push_back({static_cast<std::int64_t>(g * grains + i), static_cast<std::int64_t>(g * grains + j),
                              force(rng), force(rng)});
  return f;
}

json run_get(unsigned short port, const std::string& run) {
  return client::RpcClient("127.0.0.1", port).call("run.get", {{"run", run}});
}

TEST(FrameBounds, FramesOutOfBoundsAreRejectedWithTheirReasonAndTheRunGoesOn) {
  constexpr int kDomain = 213;
  testing::TempDir tmp;
  ServerProcess server =
      start_server(tmp.path() / "data", kDomain, tmp.path() / "server.log", {"--threads", "2", "--max-frame-mib", "1"});
  dds::FramePublisher p = publisher(kDomain);
  wait_for_reader(p);
  const std::string run = "bounded";
  p.publish(announcement(run, "bounds", 7));
  // An announcement whose parameters nest 2000 deep (4000 bytes, within the IDL's bound).
  RunInfo deep = announcement("deep-config", "bounds", 1);
  deep.config_json = std::string(2000, '[') + std::string(2000, ']');
  p.publish(deep);

  std::vector<RunFrame> frames;
  for (std::uint32_t k = 0; k < 7; ++k) frames.push_back(lammps_run_frame(run, k, 8 + k % 3));
  frames[1].header.rho = std::numeric_limits<double>::quiet_NaN();
  frames[2].header.rho = 1e300;
  frames[3].header.z = std::numeric_limits<double>::infinity();
  // 20 000 grains in a chain: 20 000 x 32 + 19 999 x 32 bytes, above 1 MiB.
  frames[4].frame.particles.clear();
  frames[4].frame.particle_count = 20000;
  frames[4].frame.contacts.clear();
  for (std::int64_t k = 0; k + 1 < 20000; ++k) frames[4].frame.contacts.push_back({k, k + 1, 1.0, 0.5});
  // 40 grains all touching each other: 39 contacts per grain.
  frames[5].frame = cliques(40, 1, 5);
  frames[5].frame.label = frame_label(run, 5);
  for (const RunFrame& f : frames) p.publish(f);

  const json summary = wait_for_frames(server.port, run, 7, 120s);
  EXPECT_EQ(summary["frames"], 2);
  EXPECT_EQ(summary["rejected"], 5);
  const json got = run_get(server.port, run);
  const std::vector<std::pair<int, std::string>> expected = {
      {1, "run bounded frame 1: header rejected: rho = nan is not a finite number in [0, 2]"},
      {2, "run bounded frame 2: header rejected: rho = 1e+300 is not a finite number in [0, 2]"},
      {3, "run bounded frame 3: header rejected: z = inf is not a finite number in [0, 48]"},
      {4,
       "run bounded frame 4: refused unread: its 20000 grains and 19999 contacts hold 1.22 MiB, above the bound "
       "on one frame (fnet-server --max-frame-mib), 1 MiB"},
      {5, "run bounded frame 5: 39 contacts per grain"},
  };
  ASSERT_EQ(got["rejected_frames"].size(), expected.size()) << got.dump();
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const json& r = got["rejected_frames"][k];
    EXPECT_EQ(r["frame"], expected[k].first);
    EXPECT_EQ(r["reason"].get<std::string>().rfind(expected[k].second, 0), 0u) << r["reason"];
  }
  EXPECT_NE(got["rejected_frames"][4]["reason"].get<std::string>().find("exceed the bound of 24"), std::string::npos);
  // The run went on: frame 6 measured from frame 0, the last accepted.
  const json series =
      client::RpcClient("127.0.0.1", server.port).call("series.get", {{"run", run}, {"metric", "bottleneck"}});
  EXPECT_EQ(series["frame"], json::array({0, 6}));
  EXPECT_EQ(series["previous"], json::array({nullptr, 0}));
  // The ensemble's curve has the accepted frames.
  const json curve = client::RpcClient("127.0.0.1", server.port)
                         .call("ensemble.series", {{"ensemble", "bounds"}, {"metric", "bottleneck"}});
  EXPECT_EQ(curve["runs"], json::array({run}));
  EXPECT_FALSE(curve.contains("left_out"));
  // The announcement nested too deep was refused, by name.
  const json status = client::RpcClient("127.0.0.1", server.port).call("server.status");
  EXPECT_NE(status.dump().find("run announcement rejected: run deep-config: config_json is nested deeper than 32 "
                               "levels"),
            std::string::npos)
      << status.dump();
  EXPECT_EQ(server.process->stop(), 0);
}

// A store written before frames' headers were checked, holding rho = 1e300 and NaN, z = inf.
TEST(FrameBounds, EnsembleSeriesLeavesOutStoredFramesWhoseHeaderNoCurveCanPlace) {
  constexpr int kDomain = 214;
  testing::TempDir tmp;
  const fs::path data = tmp.path() / "data";
  fs::create_directories(data);
  for (const std::string run : {"old-a", "old-b"}) {
    StoreWriter w(store_path(data, run), run);
    w.write_info(announcement(run, "old", 4));
    std::shared_ptr<const AnalyzedFrame> previous;
    for (std::uint32_t k = 0; k < 4; ++k) {
      RunFrame f = lammps_run_frame(run, k, 7 + k);
      if (run == "old-a" && k == 1) f.header.rho = 1e300;
      if (run == "old-a" && k == 2) f.header.rho = std::numeric_limits<double>::quiet_NaN();
      if (run == "old-b" && k == 3) f.header.z = std::numeric_limits<double>::infinity();
      AnalyzedFrame a;
      a.header = f.header;
      a.diagrams = analyze_frame(f.frame);
      if (previous) {
        a.previous = previous->header.index;
        a.distances = step_distances(previous->diagrams, a.diagrams);
      }
      w.append(a);
      previous = std::make_shared<const AnalyzedFrame>(std::move(a));
    }
  }
  ServerProcess server = start_server(data, kDomain, tmp.path() / "server.log");
  const json curve = client::RpcClient("127.0.0.1", server.port)
                         .call("ensemble.series", {{"ensemble", "old"}, {"metric", "bottleneck"}});
  EXPECT_EQ(curve["runs"], json::array({"old-a", "old-b"}));
  EXPECT_EQ(curve["left_out"],
            json::array({"run old-a frame 1: left out: rho = 1e+300 is not a finite number in [0, 2]",
                         "run old-a frame 2: left out: rho = nan is not a finite number in [0, 2]",
                         "run old-b frame 3: left out: z = inf is not a finite number in [0, 48]"}));
  // The values binned: frame 3 of old-a and frames 1, 2 of old-b (a first frame has none).
  std::size_t n = 0;
  for (const json& v : curve["n"]) n += v.get<std::size_t>();
  EXPECT_EQ(n, 3u);
  EXPECT_EQ(server.process->stop(), 0);
}

// The run's frames settled so far (committed or rejected), from runs.list.
std::map<std::string, std::size_t> settled(client::RpcClient& rpc) {
  std::map<std::string, std::size_t> out;
  const json listed = rpc.call("runs.list");  // iterating a temporary's member would dangle
  for (const json& r : listed["runs"])
    out[r["run"]] = r["frames"].get<std::size_t>() + r["rejected"].get<std::size_t>();
  return out;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// A run of heavy frames within the bounds (50 groups of 25 grains all touching: 24 contacts per
// grain, seconds of analysis each) is held by the server when an ordinary run's frames
// arrive. First in, first out, the ordinary
// frames would wait for nearly all the heavy ones; served in turn, each waits for about one heavy
// job. FNET_SERVER_UNDER_TEST names another build's fnet-server to measure it the same way
// (tests/bench/README.md).
TEST(FairScheduling, AnOrdinaryRunIsNotKeptWaitingByAnotherRunsHeavyFrames) {
  constexpr int kDomain = 215;
  constexpr std::uint32_t kHeavy = 12, kOrdinary = 5;
  const char* under_test = std::getenv("FNET_SERVER_UNDER_TEST");
  if (under_test && !*under_test) under_test = nullptr;
  testing::TempDir tmp;
  ServerProcess server = start_server(tmp.path() / "data", kDomain, tmp.path() / "server.log", {"--threads", "2"},
                                      under_test ? under_test : FNET_SERVER);
  client::RpcClient rpc("127.0.0.1", server.port);
  dds::FramePublisher p = publisher(kDomain);
  wait_for_reader(p);
  p.publish(announcement("heavy", "", kHeavy));
  p.publish(announcement("ordinary", "", kOrdinary));
  const auto heavy_start = std::chrono::steady_clock::now();
  for (std::uint32_t k = 0; k < kHeavy; ++k) {
    RunFrame f;
    f.header = {"heavy", k, 1000ull * k, 0.1 * k, 0.85, 4.0};
    f.frame = cliques(25, 50, 100 + k);
    f.frame.label = frame_label("heavy", k);
    p.publish(f);
  }
  // Every heavy frame is held (pending or done) before the ordinary run starts.
  const auto deadline = heavy_start + 60s;
  while (std::chrono::steady_clock::now() < deadline) {
    const json listed = rpc.call("runs.list");
    std::size_t held = 0;
    for (const json& r : listed["runs"])
      if (r["run"] == "heavy") held = r["frames"].get<std::size_t>() + r["pending"].get<std::size_t>();
    if (held == kHeavy) break;
    std::this_thread::sleep_for(20ms);
  }
  const std::size_t heavy_before = settled(rpc)["heavy"];
  const auto ordinary_start = std::chrono::steady_clock::now();
  for (std::uint32_t k = 0; k < kOrdinary; ++k) p.publish(lammps_run_frame("ordinary", k, 6 + k));
  std::vector<double> latency;
  std::size_t heavy_when_ordinary_done = 0;
  while (latency.size() < kOrdinary && seconds_since(ordinary_start) < 300) {
    const auto now = settled(rpc);
    const auto it = now.find("ordinary");
    while (it != now.end() && latency.size() < it->second) latency.push_back(seconds_since(ordinary_start));
    heavy_when_ordinary_done = now.count("heavy") ? now.at("heavy") : 0;
    std::this_thread::sleep_for(20ms);
  }
  ASSERT_EQ(latency.size(), kOrdinary);
  wait_for_frames(server.port, "heavy", kHeavy, 600s);
  const double heavy_total = seconds_since(heavy_start);
  std::printf("heavy frames settled when the ordinary run started: %zu of %u; when it was done: %zu\n", heavy_before,
              kHeavy, heavy_when_ordinary_done);
  std::printf("ordinary frames committed after (s):");
  for (const double t : latency) std::printf(" %.2f", t);
  std::printf("\nheavy run: %u frames in %.2f s (%.2f s of the pool per frame, 2 threads)\n", kHeavy, heavy_total,
              2 * heavy_total / kHeavy);
  EXPECT_LE(heavy_when_ordinary_done, kHeavy / 2);
  EXPECT_LT(latency.back(), heavy_total / 3);
  EXPECT_EQ(server.process->stop(), 0);
}

}  // namespace
}  // namespace fnet::e2e
