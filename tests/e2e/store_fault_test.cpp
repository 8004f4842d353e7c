// Store faults are run faults, with real processes, a real filesystem and real limits: a disk that
// fills while fnet-simd streams (a tmpfs in a mount namespace of this test's own, so root only),
// a server at its file-descriptor limit (prlimit), the stores of finished runs closed, and a stop
// bounded in time with a heavy frame in analysis. Each ends with nothing lost that was reported
// committed: every frame the API counted, or sent to a subscriber, is in the store.
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <sys/mount.h>
#include <thread>

#include <gtest/gtest.h>

#include "client/rpc/rpc_client.hpp"
#include "common/store/analysis_store.hpp"
#include "tests/e2e/line_connection.hpp"
#include "tests/e2e/service_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

// DDS domains 204-207 (CONTRIBUTING.md).
constexpr int kFullDiskDomain = 204, kFdLimitDomain = 205, kClosedStoresDomain = 206, kStopDomain = 207;

json fault_run_summary(unsigned short port, const std::string& run) {
  client::RpcClient rpc("127.0.0.1", port);
  const json listed = rpc.call("runs.list");
  for (const json& r : listed["runs"])
    if (r["run"] == run) return r;
  return nullptr;
}

// Polls runs.list until `done` holds for the run's summary; fails the test with the last summary
// after `limit`.
json fault_wait_until(unsigned short port, const std::string& run, const std::function<bool(const json&)>& done,
                      std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  json last;
  while (std::chrono::steady_clock::now() < deadline) {
    last = fault_run_summary(port, run);
    if (!last.is_null() && done(last)) return last;
    std::this_thread::sleep_for(100ms);
  }
  ADD_FAILURE() << "run " << run << " never reached the expected state: " << last.dump();
  return last;
}

// The frame indices series.get serves for the run: the frames the API reports committed.
std::set<std::uint32_t> fault_served_frames(unsigned short port, const std::string& run) {
  client::RpcClient rpc("127.0.0.1", port);
  const json s = rpc.call("series.get", {{"run", run}, {"metric", "bottleneck"}});
  return {s["frame"].begin(), s["frame"].end()};
}

std::set<std::uint32_t> fault_stored_frames(const fs::path& data_dir, const std::string& run) {
  std::set<std::uint32_t> out;
  for (const AnalyzedFrame& f : read_store(store_path(data_dir, run)).frames) out.insert(f.header.index);
  return out;
}

void expect_all_in(const std::set<std::uint32_t>& reported, const std::set<std::uint32_t>& stored,
                   const std::string& what) {
  for (const std::uint32_t k : reported) EXPECT_TRUE(stored.count(k)) << what << ": frame " << k << " is not stored";
}

// A tmpfs of `size` at `dir`, in a mount namespace this test process enters alone (its children
// share it, nothing outside sees it; it ends with the process). Unmounted at scope exit.
class PrivateTmpfs {
 public:
  PrivateTmpfs(const fs::path& dir, const std::string& size) : dir_(dir) {
    fs::create_directories(dir);
    if (unshare(CLONE_NEWNS) != 0 || mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
        mount("tmpfs", dir.c_str(), "tmpfs", 0, ("size=" + size).c_str()) != 0)
      throw std::runtime_error("cannot mount a private tmpfs at " + dir.string() + ": " + std::strerror(errno));
  }
  ~PrivateTmpfs() { umount2(dir_.c_str(), MNT_DETACH); }

 private:
  fs::path dir_;
};

// The port fnet-server's first line names; 0 (and a failure naming its log) if it never came.
unsigned short fault_port(Process& server, const fs::path& log) {
  const auto line = server.read_line(30s);
  std::smatch port;
  if (line && std::regex_search(*line, port, std::regex(":(\\d+) ")))
    return static_cast<unsigned short>(std::stoi(port[1]));
  ADD_FAILURE() << "fnet-server did not start: " << read_file(log);
  return 0;
}

// Writes `file` until the filesystem is full.
void fill_up(const fs::path& file) {
  std::ofstream out(file, std::ios::binary);
  const std::string block(1 << 16, 'x');
  while (out.write(block.data(), static_cast<std::streamsize>(block.size()))) {
  }
}

// 1 000 disks, 24 frames at 20x the paper's wall speed, DDS the only output: about 5 s of frames.
std::vector<std::string> streaming_run(const std::string& run_id, int domain) {
  return {"--particles", "1000",     "--compression-speed",  "1e-3",   "--frames", "24", "--seed", "3", "--run-id",
          run_id,        "--domain", std::to_string(domain), "--quiet"};
}

TEST(StoreFault, FullDiskFailsTheRunEverywhereUntilSpaceReturnsAndLosesNothingCommitted) {
  if (geteuid() != 0) GTEST_SKIP() << "a private tmpfs needs root";
  testing::TempDir tmp;
  const fs::path data = tmp.path() / "data";
  PrivateTmpfs disk(data, "64m");
  // HDF5 cannot close a file whose flush failed: what it allocated for it stays (some 70 kB per
  // fault), inside libhdf5, whose leaks common/store/hdf5_io.cpp suppresses under LeakSanitizer.
  std::map<std::string, std::string> env = dds_environment();
  ServerProcess server;
  server.process =
      std::make_unique<Process>(FNET_SERVER,
                                std::vector<std::string>{"--data-dir", data.string(), "--port", "0", "--domain",
                                                         std::to_string(kFullDiskDomain), "--store-retry", "1"},
                                tmp.path() / "server.log", env);
  server.port = fault_port(*server.process, tmp.path() / "server.log");
  LineConnection watcher(server.port);  // a subscriber: what it is sent must be in the store
  watcher.call("series.subscribe", {{"run", "full-disk"}});
  Process simd(FNET_SIMD, streaming_run("full-disk", kFullDiskDomain), tmp.path() / "simd.log", dds_environment());

  // The disk fills while the run streams.
  fault_wait_until(
      server.port, "full-disk", [](const json& r) { return r["frames"] >= 2; }, 120s);
  fill_up(data / "filler");
  const json faulty = fault_wait_until(
      server.port, "full-disk", [](const json& r) { return r["store_fault"].is_string(); }, 60s);
  EXPECT_NE(faulty["store_fault"].get<std::string>().find("No space left on device"), std::string::npos) << faulty;
  client::RpcClient rpc("127.0.0.1", server.port);
  const json status = rpc.call("server.status");
  ASSERT_EQ(status["stores"]["faults"].size(), 1u) << status.dump();
  EXPECT_EQ(status["stores"]["faults"][0]["run"], "full-disk");
  EXPECT_EQ(rpc.call("run.get", {{"run", "full-disk"}})["store_fault"], faulty["store_fault"]);
  const Outcome ctl = run_fnetctl(server.port, {"status"}, tmp.path() / "fnetctl.log");
  EXPECT_EQ(ctl.code, 5) << ctl.err;
  EXPECT_NE(ctl.out.find("store fault: run full-disk: "), std::string::npos) << ctl.out;

  // The publisher ends while the fault lasts: non-zero, naming the run and the reason.
  const std::optional<int> code = simd.wait(120s);
  ASSERT_TRUE(code.has_value()) << "fnet-simd did not end";
  const std::string err = read_file(tmp.path() / "simd.log");
  EXPECT_EQ(*code, 4) << err;
  EXPECT_NE(err.find("run full-disk is not stored"), std::string::npos) << err;
  EXPECT_NE(err.find("No space left on device"), std::string::npos) << err;

  // Meanwhile only stored frames are reported committed, and sent to the subscriber.
  const json during = fault_run_summary(server.port, "full-disk");
  EXPECT_TRUE(during["store_fault"].is_string()) << during;
  EXPECT_GT(during["unstored"].get<int>() + during["pending"].get<int>(), 0) << during;
  const std::set<std::uint32_t> reported = fault_served_frames(server.port, "full-disk");
  EXPECT_EQ(reported.size(), during["frames"].get<std::size_t>());
  EXPECT_LT(reported.size(), 24u) << "the disk filled after the whole run";
  while (const auto n = watcher.next(200ms)) watcher.notifications.push_back(*n);
  std::set<std::uint32_t> sent;
  for (const json& n : watcher.notifications) sent.insert(n["params"]["frame"].get<std::uint32_t>());
  const std::set<std::uint32_t> stored = fault_stored_frames(data, "full-disk");
  expect_all_in(reported, stored, "reported during the fault");
  expect_all_in(sent, stored, "sent to a subscriber during the fault");

  // Space returns: the queued frames are written, nothing dropped.
  fs::remove(data / "filler");
  const json healed = fault_wait_until(
      server.port, "full-disk",
      [](const json& r) { return r["store_fault"].is_null() && r["frames"] == 24 && r["unstored"] == 0; }, 60s);
  EXPECT_EQ(healed["rejected"], 0);
  EXPECT_EQ(fault_stored_frames(data, "full-disk").size(), 24u);
  EXPECT_EQ(server.process->stop(), 0);

  // And a restart serves them all from the store.
  ServerProcess again = e2e::start_server(data, kFullDiskDomain, tmp.path() / "server2.log");
  EXPECT_EQ(fault_served_frames(again.port, "full-disk").size(), 24u);
  EXPECT_EQ(again.process->stop(), 0);
}

// CPU seconds (user + system) the process has used.
double cpu_seconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  std::istringstream fields(text.substr(text.rfind(')') + 2));
  std::string field;
  double ticks = 0;
  for (int k = 3; fields >> field && k <= 15; ++k)
    if (k == 14 || k == 15) ticks += std::stod(field);
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

std::size_t open_fds(pid_t pid) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator("/proc/" + std::to_string(pid) + "/fd")) ++n;
  return n;
}

TEST(StoreFault, AtItsFileLimitTheServerAnswersBacksOffAndFailsNewRunsUntilDescriptorsReturn) {
#ifdef __SANITIZE_ADDRESS__
  GTEST_SKIP() << "UBSan checks a dynamic type it has not seen through a pipe: with no descriptor left it "
                  "reports a false error";
#endif
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {0, 1, 2});
  // fnet-server under a limit of 48 descriptors (prlimit execs it: the pid is the server's).
  ServerProcess server;
  {
    std::vector<std::string> args{"--nofile=48:48", FNET_SERVER, "--data-dir",    (tmp.path() / "data").string(),
                                  "--port",         "0",         "--domain",      std::to_string(kFdLimitDomain),
                                  "--threads",      "2",         "--store-retry", "1"};
    server.process = std::make_unique<Process>("/usr/bin/prlimit", args, tmp.path() / "server.log", dds_environment());
    server.port = fault_port(*server.process, tmp.path() / "server.log");
    ASSERT_NE(server.port, 0);
  }
  // Finished runs hold no descriptor: a few before the limit is reached.
  for (const std::string run : {"before-1", "before-2"}) {
    ASSERT_EQ(publish(run_dir, run, kFdLimitDomain, tmp.path() / (run + ".log"))->wait(120s), 0);
    fault_wait_until(
        server.port, run, [](const json& r) { return r["frames"] == 3; }, 60s);
  }
  LineConnection kept(server.port);  // opened before the limit: it must keep answering
  fault_wait_until(
      server.port, "before-2",
      [&](const json&) { return kept.call("server.status", json::object())["result"]["stores"]["open"] == 0; }, 30s);

  // Idle connections take every descriptor left; the kernel queues the rest unaccepted.
  std::vector<std::unique_ptr<LineConnection>> idle;
  for (int k = 0; k < 64; ++k) idle.push_back(std::make_unique<LineConnection>(server.port));
  std::this_thread::sleep_for(1s);
  ASSERT_GE(open_fds(server.process->pid()), 47u) << "the server is not at its limit";
  const double cpu_before = cpu_seconds(server.process->pid());
  std::this_thread::sleep_for(3s);
  const double cpu = cpu_seconds(server.process->pid()) - cpu_before;
  // Idle, it wakes a few times a second (ingest, store tending): a spinning accept loop takes far
  // more, even on a loaded machine (0.44 s in 3 s measured with two builds running).
  EXPECT_LT(cpu, 0.15) << "the server spins at its file limit: " << cpu << " s of CPU in 3 s";
  EXPECT_TRUE(kept.call("runs.list", json::object()).contains("result"));

  // A new run cannot open its store: a store fault, said to the API and to its publisher.
  auto pub = publish(run_dir, "at-limit", kFdLimitDomain, tmp.path() / "at-limit.log", 0, 0, 30);
  const std::optional<int> code = pub->wait(120s);
  ASSERT_TRUE(code.has_value());
  const std::string err = read_file(tmp.path() / "at-limit.log");
  EXPECT_EQ(*code, 4) << err;
  EXPECT_NE(err.find("run at-limit is not stored"), std::string::npos) << err;
  const json listed = kept.call("runs.list", json::object())["result"];
  json at_limit;
  for (const json& r : listed["runs"])
    if (r["run"] == "at-limit") at_limit = r;
  ASSERT_TRUE(at_limit.is_object()) << listed;
  EXPECT_NE(at_limit["store_fault"].get<std::string>().find("Too many open files"), std::string::npos) << at_limit;
  EXPECT_EQ(at_limit["frames"], 0) << at_limit;

  // Descriptors return: the server accepts again and the run's frames reach its store.
  idle.clear();
  const json healed = fault_wait_until(
      server.port, "at-limit", [](const json& r) { return r["store_fault"].is_null() && r["frames"] == 3; }, 60s);
  EXPECT_EQ(fault_stored_frames(tmp.path() / "data", "at-limit").size(), 3u);
  EXPECT_EQ(server.process->stop(), 0);
}

TEST(StoreFault, FinishedRunsCloseTheirStoresWhichStillServeTheirNetworks) {
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {0, 1});
  ServerProcess server = e2e::start_server(tmp.path() / "data", kClosedStoresDomain, tmp.path() / "server.log");
  const pid_t pid = server.process->pid();
  client::RpcClient rpc("127.0.0.1", server.port);
  std::size_t fds_after_first = 0;
  for (int k = 0; k < 12; ++k) {
    const std::string run = "closed-" + std::to_string(k);
    ASSERT_EQ(publish(run_dir, run, kClosedStoresDomain, tmp.path() / (run + ".log"))->wait(120s), 0);
    fault_wait_until(
        server.port, run, [](const json& r) { return r["frames"] == 2; }, 60s);
    fault_wait_until(
        server.port, run, [&](const json&) { return rpc.call("server.status")["stores"]["open"] == 0; }, 10s);
    if (k == 0) fds_after_first = open_fds(pid);
  }
  EXPECT_LE(open_fds(pid), fds_after_first + 2) << "descriptors grow with the runs";
  // A closed store is read on demand.
  const json net = rpc.call("network.get", {{"run", "closed-3"}, {"frame", 1}});
  EXPECT_EQ(net["frame"], 1);
  EXPECT_EQ(rpc.call("server.status")["stores"]["open"], 0);
  EXPECT_EQ(server.process->stop(), 0);
}

// A frame whose every pair of 300 grains touches: about a minute of persistence per network.
void heavy_frame(const fs::path& dir, int index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d", index);
  std::ofstream particles(dir / (std::string(name) + "_particles.csv")),
      contacts(dir / (std::string(name) + "_contacts.csv"));
  constexpr int kGrains = 300;
  particles << "id,x,y,r\n";
  for (int i = 0; i < kGrains; ++i)
    particles << i << "," << 10 * std::cos(2 * M_PI * i / kGrains) << "," << 10 * std::sin(2 * M_PI * i / kGrains)
              << ",0.5\n";
  contacts << "i,j,fn,ft\n";
  long long k = 0;
  for (int i = 0; i < kGrains; ++i)
    for (int j = i + 1; j < kGrains; ++j, ++k)
      contacts << i << "," << j << "," << 1 + static_cast<int>(k * 7919 % 1000) / 100.0 << ","
               << 0.1 + static_cast<int>(k * 104729 % 1000) / 1000.0 << "\n";
  std::ofstream(dir / "index.csv", std::ios::app) << index << ",1000000,0.8,4\n";
}

TEST(StoreFault, SigtermEndsWithinTheStopTimeoutWithAHeavyFrameInAnalysis) {
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {0});
  heavy_frame(run_dir, 1);
  ServerProcess server = e2e::start_server(tmp.path() / "data", kStopDomain, tmp.path() / "server.log",
                                           {"--threads", "1", "--stop-timeout", "2", "--max-contacts-per-grain", "0"});
  auto pub = publish(run_dir, "heavy", kStopDomain, tmp.path() / "publish.log", 0, 60);
  const json busy = fault_wait_until(
      server.port, "heavy", [](const json& r) { return r["frames"] == 1 && r["pending"] == 1; }, 120s);
  const std::set<std::uint32_t> reported = fault_served_frames(server.port, "heavy");
  std::this_thread::sleep_for(1s);
  ASSERT_EQ(fault_run_summary(server.port, "heavy")["pending"], 1) << "the heavy frame was analyzed already";
  const auto sent = std::chrono::steady_clock::now();
  server.process->signal(SIGTERM);
  const std::optional<int> code = server.process->wait(20s);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  ASSERT_TRUE(code.has_value()) << "SIGTERM did not end the server";
  EXPECT_EQ(*code, 0);
  EXPECT_LT(seconds, 2 + 3.0) << "the stop took longer than --stop-timeout 2 and a margin";
  EXPECT_NE(read_file(tmp.path() / "server.log").find("abandoned"), std::string::npos);
  expect_all_in(reported, fault_stored_frames(tmp.path() / "data", "heavy"), "reported before SIGTERM");
  pub->stop();
}

}  // namespace
}  // namespace fnet::e2e
