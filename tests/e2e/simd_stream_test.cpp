// fnet-simd streaming for real: a subscriber on loopback receives every frame of a short run
// bit-exact (the HDF5 run file written alongside is the reference), and fnet-server's series for
// that run equals the offline analysis of the run file.
#include <algorithm>
#include <regex>
#include <thread>

#include <gtest/gtest.h>

#include "client/rpc/rpc_client.hpp"
#include "common/store/analysis_store.hpp"
#include "common/store/run_file.hpp"
#include "common/transport/frame_transport.hpp"
#include "tests/e2e/process.hpp"
#include "tests/support/run_frame_compare.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

using testing::expect_bit_exact;

// A short, fast compression: 150 disks at 40x the paper's wall speed, 8 frames.
std::vector<std::string> small_run(const std::string& run_id, int domain, const fs::path& out) {
  return {"--particles",
          "150",
          "--box",
          "13.7",
          "--compression-speed",
          "2e-3",
          "--frames",
          "8",
          "--seed",
          "11",
          "--run-id",
          run_id,
          "--domain",
          std::to_string(domain),
          "--out",
          out.string(),
          "--linger",
          "30",
          "--quiet"};
}

// fnet-server on `domain` with its data and log under `dir`.
Process start_server(const fs::path& dir, int domain) {
  return Process(FNET_SERVER,
                 {"--data-dir", (dir / "data").string(), "--port", "0", "--domain", std::to_string(domain)},
                 dir / "server.log", dds_environment());
}

// The port of its "listening on 127.0.0.1:PORT" line, 0 if it never came.
unsigned short listening_port(Process& server) {
  const auto line = server.read_line(30s);
  std::smatch m;
  if (!line || !std::regex_search(*line, m, std::regex(":(\\d+) "))) return 0;
  return static_cast<unsigned short>(std::stoi(m[1]));
}

TEST(SimdStream, SubscriberReceivesEveryFrameBitExact) {
  testing::TempDir tmp;
  // The daemon starts first (no DDS in this process before the fork); the subscriber joins late
  // and is served from the durability history while the daemon lingers.
  Process simd(FNET_SIMD, small_run("bits", 41, tmp.path() / "run.h5"), tmp.path() / "simd.log", dds_environment());
  setenv("CYCLONEDDS_URI", dds_environment().at("CYCLONEDDS_URI").c_str(), 1);
  dds::FrameSubscriber subscriber(41);
  std::vector<RunFrame> got;
  std::vector<RunInfo> infos;
  const auto deadline = std::chrono::steady_clock::now() + 300s;
  while (got.size() < 8 && std::chrono::steady_clock::now() < deadline) {
    dds::Received r = subscriber.take(DDS_MSECS(200));
    for (auto& f : r.frames) got.push_back(std::move(f));
    for (auto& i : r.infos) infos.push_back(std::move(i));
    ASSERT_TRUE(r.malformed.empty());
  }
  ASSERT_EQ(got.size(), 8u) << "see " << (tmp.path() / "simd.log");
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_EQ(infos[0].particles, 150u);
  EXPECT_EQ(infos[0].frames, 8u);
  // The daemon closes its run file right after the last frame (HDF5 locks it until then).
  RunFileContents file;
  for (int k = 0;; ++k) {
    try {
      file = read_run_file(tmp.path() / "run.h5");
      break;
    } catch (const h5::Error&) {
      if (k == 300) throw;
      std::this_thread::sleep_for(100ms);
    }
  }
  EXPECT_EQ(file.info, infos[0]);
  ASSERT_EQ(file.frames.size(), 8u);
  for (std::size_t k = 0; k < 8; ++k) {
    expect_bit_exact(file.frames[k], got[k]);
    EXPECT_NO_THROW(validate(got[k].frame)) << "frame " << k;
  }
  EXPECT_GT(got.back().header.rho, 0.89);  // the compression reached its end
  simd.stop();
}

// --ensemble without --run-id: the run is NAME-sSEED and its announcement names the ensemble, on
// DDS (the server's run.get) and in the run file.
TEST(SimdStream, EnsembleNameIsAnnouncedAndMakesTheRunId) {
  testing::TempDir tmp;
  Process server = start_server(tmp.path(), 43);
  const unsigned short port = listening_port(server);
  ASSERT_NE(port, 0) << "see " << (tmp.path() / "server.log");
  std::vector<std::string> args = small_run("unused", 43, tmp.path() / "run.h5");
  for (const char* flag : {"--run-id", "--linger"}) {
    const auto at = std::find(args.begin(), args.end(), flag);
    args.erase(at, at + 2);
  }
  *(std::find(args.begin(), args.end(), "--frames") + 1) = "2";
  args.insert(args.end(), {"--ensemble", "mu05"});
  Process simd(FNET_SIMD, args, tmp.path() / "simd.log", dds_environment());
  client::RpcClient rpc("127.0.0.1", port);
  client::json run;
  for (int k = 0; k < 3000 && run.is_null(); ++k) {
    const client::json listed = rpc.call("runs.list");
    if (!listed["runs"].empty() && listed["runs"][0]["announced"] == true)
      run = rpc.call("run.get", {{"run", listed["runs"][0]["run"]}});
    else
      std::this_thread::sleep_for(100ms);
  }
  ASSERT_FALSE(run.is_null()) << "see " << (tmp.path() / "server.log");
  EXPECT_EQ(run["run"], "mu05-s11");
  EXPECT_EQ(run["parameters"]["ensemble"], "mu05");
  EXPECT_EQ(simd.wait(120s), 0);
  EXPECT_EQ(read_run_file(tmp.path() / "run.h5").info.ensemble, "mu05");
  EXPECT_EQ(server.stop(), 0);
}

TEST(SimdStream, ServerSeriesOfASimulatedRunEqualsOfflineAnalysisOfItsRunFile) {
  testing::TempDir tmp;
  Process server = start_server(tmp.path(), 42);
  const unsigned short port = listening_port(server);
  ASSERT_NE(port, 0) << "see " << (tmp.path() / "server.log");
  Process simd(FNET_SIMD, small_run("sim", 42, tmp.path() / "run.h5"), tmp.path() / "simd.log", dds_environment());
  client::RpcClient rpc("127.0.0.1", port);
  client::json run;
  for (int k = 0; k < 3000; ++k) {
    const client::json listed = rpc.call("runs.list");
    if (!listed["runs"].empty() && listed["runs"][0]["frames"] == 8) {
      run = listed["runs"][0];
      break;
    }
    std::this_thread::sleep_for(100ms);
  }
  ASSERT_EQ(run["frames"], 8) << "see " << (tmp.path() / "server.log");
  EXPECT_EQ(run["planned_frames"], 8);
  simd.stop();
  Process offline(
      FNET_ANALYZE,
      {"store", "--run-file", (tmp.path() / "run.h5").string(), "--data-dir", (tmp.path() / "offline").string()},
      tmp.path() / "offline.log");
  ASSERT_EQ(offline.wait(300s), 0);
  const StoredRun expected = read_store(store_path(tmp.path() / "offline", "sim"));
  ASSERT_EQ(expected.frames.size(), 8u);
  const client::json series =
      rpc.call("series.get", {{"run", "sim"}, {"metric", "wasserstein1"}, {"dim", 1}, {"force", "tangential"}});
  for (std::size_t k = 1; k < 8; ++k)
    EXPECT_EQ(series["value"][k].get<double>(),
              expected.frames[k].distances(Metric::wasserstein1, 1, ForceKind::tangential));
  EXPECT_EQ(server.stop(), 0);
}

}  // namespace
}  // namespace fnet::e2e
