// Corrupted and hostile files in fnet-server's data directory: each is refused alone, naming its
// file and why, within a bounded time, while the server starts and serves the healthy runs (DDS
// domains 227–229, 220–221). The stores are real ones written by fnet-analyze store, then damaged
// here: bits flipped in the superblock and across the file, a crafted diagram offset, a run id that
// is a path, a global heap that HDF5 reads forever; a FIFO named like a store.
#include <algorithm>
#include <chrono>
#include <string>
#include <sys/stat.h>
#include <vector>

#include <gtest/gtest.h>

#include "client/rpc/rpc_client.hpp"
#include "tests/e2e/service_process.hpp"
#include "tests/support/store_damage.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

namespace fs = std::filesystem;
using client::json;
using client::RpcClient;
using Clock = std::chrono::steady_clock;

using testing::flip_bits;
using testing::loop_global_heap;
using testing::rename_run;
using testing::set_entry;

class CorruptStore : public ::testing::Test {
 public:
  ~CorruptStore() override {
    if (server_) server_->stop();
  }

  fs::path data() const { return tmp_.path() / "data"; }

  // Three LAMMPS frames analyzed by fnet-analyze store into the data directory as run `run`.
  fs::path store(const std::string& run) {
    const fs::path csv = lammps_run(tmp_.path() / ("csv-" + run), {0, 5, 10});
    const fs::path log = tmp_.path() / ("store-" + run + ".log");
    EXPECT_EQ(store_run(csv, run, data(), log), 0) << "see " << log;
    return store_path(run);
  }
  fs::path store_path(const std::string& run) const { return data() / (run + ".h5"); }

  // Starts fnet-server on the data directory; it must be answering within `bound`.
  void start(int domain, std::chrono::seconds bound, const std::vector<std::string>& flags = {"--threads", "2"}) {
    const auto begin = Clock::now();
    ServerProcess s = start_server(data(), domain, tmp_.path() / "server.log", flags);
    server_ = std::move(s.process);
    port_ = s.port;
    call("runs.list");
    EXPECT_LT(Clock::now() - begin, bound) << "fnet-server took that long to start";
  }

  json call(const std::string& method, const json& params = json::object()) {
    return RpcClient("127.0.0.1", port_, std::chrono::seconds(20)).call(method, params);
  }

  std::vector<std::string> listed_runs() {
    std::vector<std::string> out;
    const json listed = call("runs.list");
    for (const json& r : listed["runs"]) out.push_back(r["run"]);
    return out;
  }

  // The message among `messages` that names `file`; fails when there is none.
  static std::string naming(const json& messages, const std::string& file) {
    for (const json& m : messages)
      if (m.get<std::string>().find(file) != std::string::npos) return m;
    ADD_FAILURE() << "no message names " << file << " in " << messages.dump();
    return "";
  }

  // The healthy run is served whole: three frames and the network of each.
  void expect_healthy_served(const std::string& run) {
    for (const int frame : {0, 1, 2})
      EXPECT_EQ(call("network.get", {{"run", run}, {"frame", frame}})["particles"].size(), 2000u) << frame;
  }

  fnet::testing::TempDir tmp_;
  std::unique_ptr<Process> server_;
  unsigned short port_ = 0;
};

TEST_F(CorruptStore, EachDamagedStoreIsRefusedAloneWithItsReasonAndTheHealthyRunIsServed) {
  store("good");
  // One bit of the root group's object header: HDF5's default SWMR reader retried it for minutes.
  flip_bits(store("header"), 100, 101, 1);
  // Diagram 0 of frame 0 ends past every point, the diagrams after it end where they should.
  set_entry(store("offset"), "offsets", 0, 1, 5, 1'000'000'000);
  // The network of frame 1 starts after it ends.
  set_entry(store("network"), "network_offsets", 1, 0, 4, 1'000'000);
  // A run id that is a path out of the data directory: the server would write the run there.
  rename_run(store("escape"), "../../escape");

  start(227, std::chrono::seconds(20));
  EXPECT_EQ(listed_runs(), std::vector<std::string>{"good"}) << call("server.status").dump();
  expect_healthy_served("good");
  const json refused = call("server.status")["refused_stores"];
  EXPECT_EQ(refused.size(), 4u) << refused.dump();
  naming(refused, "header.h5");  // its metadata fails its checksum
  EXPECT_NE(naming(refused, "offset.h5").find("offsets not ascending"), std::string::npos);
  EXPECT_NE(naming(refused, "network.h5").find("network_offsets not ordered"), std::string::npos);
  EXPECT_NE(naming(refused, "escape.h5").find("'../../escape' has a character outside"), std::string::npos);
  EXPECT_FALSE(fs::exists(tmp_.path() / "escape.h5"));
}

TEST_F(CorruptStore, BitsFlippedAcrossAStoreCostABoundedTimeAndNeverTheOtherRuns) {
  store("good");
  const fs::path flipped = store("flipped");
  flip_bits(flipped, 512, fs::file_size(flipped), 4093);

  start(228, std::chrono::seconds(20));
  const std::vector<std::string> runs = listed_runs();
  ASSERT_NE(std::find(runs.begin(), runs.end(), "good"), runs.end());
  // Served or refused, the flipped store answers each request within a bound, and the healthy
  // run is served whole after it.
  if (std::find(runs.begin(), runs.end(), "flipped") != runs.end())
    for (const int frame : {0, 1, 2}) {
      const auto begin = Clock::now();
      try {
        call("network.get", {{"run", "flipped"}, {"frame", frame}});
      } catch (const client::CallError&) {
      }
      EXPECT_LT(Clock::now() - begin, std::chrono::seconds(10)) << "network.get of frame " << frame;
    }
  else
    naming(call("server.status")["refused_stores"], "flipped.h5");
  expect_healthy_served("good");
}

TEST_F(CorruptStore, AFifoNamedLikeAStoreIsRefusedWithoutBlockingTheRescan) {
  store("good");
  ASSERT_EQ(mkfifo(store_path("pipe").c_str(), 0600), 0);
  start(229, std::chrono::seconds(20));
  const auto begin = Clock::now();
  const json rescan = call("server.rescan");
  EXPECT_LT(Clock::now() - begin, std::chrono::seconds(5));
  EXPECT_EQ(rescan["adopted"], json::array());
  EXPECT_NE(naming(rescan["problems"], "pipe.h5").find("not a regular file"), std::string::npos);
  // A store placed meanwhile is adopted by the same rescan that refuses the FIFO again.
  store("late");
  const json again = call("server.rescan");
  EXPECT_EQ(again["adopted"], json::array({"late"}));
  naming(again["problems"], "pipe.h5");
  naming(call("server.status")["refused_stores"], "pipe.h5");
  expect_healthy_served("good");
  expect_healthy_served("late");
}

// What a store's check (--store-check-seconds) says of a store whose global heap HDF5 reads forever.
const std::string kHeapLoops = "heap.h5: its check did not finish within 8 s";
// Far longer than a healthy store's check takes, even under the sanitizers on a loaded machine.
const std::vector<std::string> kCheckIn8s{"--threads", "2", "--store-check-seconds", "8"};

TEST_F(CorruptStore, AStoreThatHDF5ReadsForeverIsRefusedAtItsCheckDeadlineAndTheServerStarts) {
  store("good");
  loop_global_heap(store("heap"));
  start(220, std::chrono::seconds(25), kCheckIn8s);
  EXPECT_EQ(listed_runs(), std::vector<std::string>{"good"});
  expect_healthy_served("good");
  const json refused = call("server.status")["refused_stores"];
  EXPECT_EQ(refused.size(), 1u) << refused.dump();
  EXPECT_NE(naming(refused, "heap.h5").find(kHeapLoops), std::string::npos);
}

TEST_F(CorruptStore, ARescanRefusesAStoreThatHDF5ReadsForeverChecksItOnceAndItsRunIsNeverReadInTheServer) {
  store("good");
  start(221, std::chrono::seconds(20), kCheckIn8s);
  loop_global_heap(store("heap"));
  store("late");
  auto begin = Clock::now();
  const json rescan = call("server.rescan");
  EXPECT_LT(Clock::now() - begin, std::chrono::seconds(18));
  EXPECT_EQ(rescan["adopted"], json::array({"late"}));
  EXPECT_NE(naming(rescan["problems"], "heap.h5").find(kHeapLoops), std::string::npos);
  // Unchanged, it is refused again for the same reason without a second check.
  begin = Clock::now();
  const json again = call("server.rescan");
  EXPECT_LT(Clock::now() - begin, std::chrono::seconds(2));
  EXPECT_EQ(again["problems"], rescan["problems"]);
  EXPECT_EQ(call("server.status")["refused_stores"], rescan["problems"]);
  // Frames of the run streamed meanwhile: its store, which the server would read to continue it,
  // is refused as a store fault, said to the publisher; the server answers throughout.
  const fs::path csv = lammps_run(tmp_.path() / "csv-stream", {0, 5, 10});
  auto pub = publish(csv, "heap", 221, tmp_.path() / "publish.log", 0, 0, 30);
  const std::optional<int> code = pub->wait(std::chrono::seconds(120));
  ASSERT_TRUE(code.has_value());
  const std::string err = read_file(tmp_.path() / "publish.log");
  EXPECT_EQ(*code, 4) << err;
  begin = Clock::now();
  const json run = call("run.get", {{"run", "heap"}});
  EXPECT_LT(Clock::now() - begin, std::chrono::seconds(2));
  EXPECT_NE(run["store_fault"].get<std::string>().find(kHeapLoops), std::string::npos) << run.dump();
  expect_healthy_served("good");
  expect_healthy_served("late");
}

}  // namespace
}  // namespace fnet::e2e
