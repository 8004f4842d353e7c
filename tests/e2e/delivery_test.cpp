// A publisher ends only when every matched reader has every frame, and says when one may not:
// fnet-analyze publish against a fnet-server that stops reading (SIGSTOP) for longer than the
// publisher's --ack-timeout fails with exit code 3 and says so; with the default timeout it waits
// the stall out and every frame is analyzed (and stored); a server killed mid-run is reported once
// DDS drops it; a publisher no reader ever matched fails too.
#include <csignal>
#include <cstdio>
#include <fstream>
#include <thread>
#include <utility>

#include <gtest/gtest.h>

#include "common/store/analysis_store.hpp"
#include "tests/e2e/service_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr int kDeliveryDomain = 201;

// Frames of four touching disks: small enough that the frames written while the server is stopped
// all fit the writer's history, so that the publisher is left waiting for acknowledgements rather
// than for a write.
constexpr int kFrames = 10;

fs::path four_disk_run(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream index(dir / "index.csv");
  index << "frame,step,rho,Z\n";
  for (int k = 0; k < kFrames; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d", k);
    std::ofstream particles(dir / (std::string(name) + "_particles.csv"));
    particles << "id,x,y,r\n0,0,0,0.5\n1,1,0,0.5\n2,0,1,0.5\n3,1,1,0.5\n";
    std::ofstream contacts(dir / (std::string(name) + "_contacts.csv"));
    contacts << "i,j,fn,ft\n0,1," << 1 + k << ",0.1\n0,2,2,0.2\n1,3,3,0.3\n2,3," << 4 + k << ",0.4\n";
    index << k << "," << 1000 * k << "," << 0.7 + 0.01 * k << ",2\n";
  }
  return dir;
}

// Resumes a stopped server however the test ends, so that its destructor can stop it.
struct Resume {
  Process& server;
  ~Resume() { server.signal(SIGCONT); }
};

// Publishes `rate` frames a second and stops the server once its first frame is committed: the later
// frames are written while it cannot acknowledge them, as long as committing the first takes less
// than the publication's (kFrames - 1) / rate seconds.
std::unique_ptr<Process> publish_while_server_stops(const fs::path& run_dir, const std::string& run,
                                                    ServerProcess& server, const fs::path& log, const char* rate,
                                                    const std::vector<std::string>& extra) {
  std::vector<std::string> args{
      "publish", "--csv-dir", run_dir.string(),    "--run-id", run, "--domain", std::to_string(kDeliveryDomain),
      "--rate",  rate,        "--wait-for-reader", "30"};
  args.insert(args.end(), extra.begin(), extra.end());
  auto publisher = std::make_unique<Process>(FNET_ANALYZE, args, log, dds_environment());
  wait_for_frames(server.port, run, 1, 60s);
  server.process->signal(SIGSTOP);
  return publisher;
}

TEST(Delivery, PublisherFailsWhenAReaderMayLackFramesAndWaitsOutAStall) {
  testing::TempDir tmp;
  const fs::path run_dir = four_disk_run(tmp.path() / "run");
  ServerProcess server = e2e::start_server(tmp.path() / "data", kDeliveryDomain, tmp.path() / "server.log");
  {
    Resume resume{*server.process};
    // Publication (4.5 s) and --ack-timeout end within the DDS lease: the reader is late, not gone.
    auto publisher = publish_while_server_stops(run_dir, "short-wait", server, tmp.path() / "short.log", "2",
                                                {"--ack-timeout", "2"});
    const std::optional<int> code = publisher->wait(60s);
    ASSERT_TRUE(code.has_value()) << "publish did not end while its reader was stopped";
    EXPECT_EQ(*code, 3);
    const std::string err = read_file(tmp.path() / "short.log");
    EXPECT_NE(err.find("not every frame was acknowledged"), std::string::npos) << err;
    EXPECT_NE(err.find("--ack-timeout 2"), std::string::npos) << err;
  }
  // Resumed: the server is intact and serves its API.
  wait_for_frames(server.port, "short-wait", 1, 30s);

  {
    Resume resume{*server.process};
    // The stall outlasts the frames' publication (at most 4.5 s after the stop) but not the DDS
    // lease (10 s), after which the stopped server would count as gone.
    auto publisher = publish_while_server_stops(run_dir, "long-wait", server, tmp.path() / "long.log", "2", {});
    std::this_thread::sleep_for(7s);
    EXPECT_FALSE(publisher->wait(0ms).has_value()) << "publish ended while its reader was stopped";
    server.process->signal(SIGCONT);
    const std::optional<int> code = publisher->wait(60s);
    ASSERT_TRUE(code.has_value());
    EXPECT_EQ(*code, 0) << read_file(tmp.path() / "long.log");
  }
  const nlohmann::json run = wait_for_frames(server.port, "long-wait", kFrames, 60s);
  EXPECT_EQ(run["frames"], kFrames) << run.dump();
  EXPECT_EQ(run["rejected"], 0) << run.dump();
  // What the API reports committed across the stall is in the store.
  for (const std::string r : {"short-wait", "long-wait"})
    EXPECT_GE(read_store(store_path(tmp.path() / "data", r)).frames.size(),
              wait_for_frames(server.port, r, 1, 30s)["frames"].get<std::size_t>())
        << r;

  {
    // Publication (9 s) goes on after the kill unless the first commit takes as long: frames are left unacknowledged.
    auto publisher = publish_while_server_stops(run_dir, "killed", server, tmp.path() / "killed.log", "1", {});
    server.process->signal(SIGKILL);
    // DDS drops a silent reader after its lease (10 s by default).
    const std::optional<int> code = publisher->wait(60s);
    ASSERT_TRUE(code.has_value());
    EXPECT_EQ(*code, 3);
    const std::string err = read_file(tmp.path() / "killed.log");
    EXPECT_NE(err.find("1 reader(s) went away during the run"), std::string::npos) << err;
  }
}

TEST(Delivery, FnetSimdWithOnlyDdsFailsWhenAReaderStopsAcknowledging) {
  testing::TempDir tmp;
  ServerProcess server = e2e::start_server(tmp.path() / "data", kDeliveryDomain + 10, tmp.path() / "server.log");
  Resume resume{*server.process};
  // A short compression of 150 disks, 8 frames, DDS its only output.
  Process simd(FNET_SIMD,
               {"--particles", "150", "--box", "13.7", "--compression-speed", "2e-3", "--frames", "8", "--seed", "11",
                "--run-id", "simd", "--domain", std::to_string(kDeliveryDomain + 10), "--ack-timeout", "2", "--quiet"},
               tmp.path() / "simd.log", dds_environment());
  wait_for_frames(server.port, "simd", 1, 120s);
  server.process->signal(SIGSTOP);
  const std::optional<int> code = simd.wait(120s);
  ASSERT_TRUE(code.has_value());
  const std::string err = read_file(tmp.path() / "simd.log");
  EXPECT_EQ(*code, 3) << err;
  EXPECT_NE(err.find("error: a DDS subscriber had not acknowledged every frame after --ack-timeout 2 s"),
            std::string::npos)
      << err;
}

// A domain no one reads: the publisher waits --wait-for-reader, then fails with exit code 3 naming
// the domain, as fnet-simd does, rather than reporting the frames published.
TEST(Delivery, PublishingToADomainNoOneReadsFails) {
  testing::TempDir tmp;
  constexpr int kUnreadDomain = 222;
  Process publisher(FNET_ANALYZE,
                    {"publish", "--csv-dir", four_disk_run(tmp.path() / "run").string(), "--run-id", "unread",
                     "--domain", std::to_string(kUnreadDomain), "--wait-for-reader", "0.5"},
                    tmp.path() / "publish.log", dds_environment());
  const std::optional<int> code = publisher.wait(60s);
  ASSERT_TRUE(code.has_value());
  const std::string err = read_file(tmp.path() / "publish.log");
  EXPECT_EQ(*code, 3) << err;
  EXPECT_NE(err.find("run unread: no reader on DDS domain 222 matched"), std::string::npos) << err;
}

}  // namespace
}  // namespace fnet::e2e
