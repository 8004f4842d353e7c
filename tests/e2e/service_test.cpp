// fnet-server end to end, with real processes on loopback: frames published over DDS by
// fnet-analyze publish (as fnet-simd streams them), the server analyzing and storing them, and
// clients on its TCP port.
#include <poll.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>

#include <gtest/gtest.h>

#include "client/rpc/rpc_client.hpp"
#include "common/analysis/frame_analysis.hpp"
#include "common/store/analysis_store.hpp"
#include "tests/e2e/line_connection.hpp"
#include "tests/e2e/planted_fcc_run.hpp"
#include "tests/e2e/process.hpp"
#include "tests/e2e/service_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

namespace fs = std::filesystem;
using client::json;
using client::RpcClient;
using namespace std::chrono_literals;

StoredRun offline_store(const fs::path& run_dir, const std::string& run_id, const fs::path& data_dir,
                        const fs::path& log) {
  EXPECT_EQ(store_run(run_dir, run_id, data_dir, log), 0) << "fnet-analyze store failed; see " << log;
  return read_store(store_path(data_dir, run_id));
}

// Every one of the twelve served series equals the offline analysis, value for value.
void expect_series_match(unsigned short port, const std::string& run, const StoredRun& offline) {
  RpcClient rpc("127.0.0.1", port);
  for (const Metric metric : kMetrics)
    for (int dim = 0; dim < 2; ++dim)
      for (const ForceKind force : kForces) {
        const json s = rpc.call(
            "series.get", {{"run", run}, {"metric", to_string(metric)}, {"dim", dim}, {"force", to_string(force)}});
        ASSERT_EQ(s["frame"].size(), offline.frames.size());
        for (std::size_t k = 0; k < offline.frames.size(); ++k) {
          const AnalyzedFrame& f = offline.frames[k];
          ASSERT_EQ(s["frame"][k], f.header.index);
          EXPECT_EQ(s["rho"][k].get<double>(), f.header.rho);
          if (!f.previous) {
            EXPECT_TRUE(s["value"][k].is_null());
            continue;
          }
          EXPECT_EQ(s["previous"][k], *f.previous);
          EXPECT_EQ(s["value"][k].get<double>(), f.distances(metric, dim, force))
              << run << " " << to_string(metric) << " pd" << dim << " " << to_string(force) << " frame "
              << f.header.index;
        }
      }
}

// rho_J: where Z first reaches 3, interpolated between the frames around the crossing. LAMMPS
// frames 6, 7, 8 have Z = 1.576, 2.812, 3.473: the crossing lies between the last two.
TEST(Service, RunsReportTheirJammingPoint) {
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {6, 7, 8});
  ServerProcess server = start_server(tmp.path() / "data", 56, tmp.path() / "server.log");
  auto pub = publish(run_dir, "jam", 56, tmp.path() / "publish.log");
  EXPECT_EQ(pub->wait(120s), 0);
  wait_for_frames(server.port, "jam", 3);
  RpcClient rpc("127.0.0.1", server.port);
  const json run = rpc.call("run.get", {{"run", "jam"}});
  const double rho7 = 0.802904, z7 = 2.8120, rho8 = 0.832639, z8 = 3.4730;
  ASSERT_TRUE(run["rho_j"].is_number()) << run.dump();
  EXPECT_NEAR(run["rho_j"].get<double>(), rho7 + (3 - z7) / (z8 - z7) * (rho8 - rho7), 1e-12);
  EXPECT_EQ(rpc.call("runs.list")["runs"][0]["rho_j"], run["rho_j"]);
  Process ctl(FNETCTL, {"--port", std::to_string(server.port), "runs"}, tmp.path() / "fnetctl.log");
  ASSERT_EQ(ctl.wait(30s), 0);
  const std::string table = ctl.read_rest();
  EXPECT_NE(table.find("rho_J"), std::string::npos) << table;
  EXPECT_NE(table.find("0.81136"), std::string::npos) << table;  // 5 significant digits
  EXPECT_EQ(server.process->stop(), 0);
}

TEST(Service, SeriesServedEqualsOfflineAnalysisAndFnetctlPrintsIt) {
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {0, 1, 2, 3, 4, 5});
  ServerProcess server = start_server(tmp.path() / "data", 31, tmp.path() / "server.log");
  auto pub = publish(run_dir, "live", 31, tmp.path() / "publish.log");
  EXPECT_EQ(pub->wait(120s), 0);
  wait_for_frames(server.port, "live", 6);
  const StoredRun offline = offline_store(run_dir, "live", tmp.path() / "offline", tmp.path() / "store.log");
  ASSERT_EQ(offline.frames.size(), 6u);
  expect_series_match(server.port, "live", offline);

  // Any q is computed on demand; with q = 1000 its q-th powers once underflowed to a series of 0s.
  // d_B <= d_Wq <= N^(1/q) d_B for diagrams of N points in all.
  RpcClient rpc("127.0.0.1", server.port);
  for (int dim = 0; dim < 2; ++dim) {
    const json s = rpc.call("series.get", {{"run", "live"}, {"metric", "wasserstein"}, {"q", 1000}, {"dim", dim}});
    ASSERT_EQ(s["value"].size(), offline.frames.size());
    for (std::size_t k = 1; k < offline.frames.size(); ++k) {
      const AnalyzedFrame& f = offline.frames[k];
      ASSERT_EQ(f.previous, offline.frames[k - 1].header.index);
      const double bottleneck = f.distances(Metric::bottleneck, dim, ForceKind::normal), value = s["value"][k];
      const auto& before = diagram_of(offline.frames[k - 1].diagrams, ForceKind::normal, dim);
      const auto points = static_cast<double>(before.size() + diagram_of(f.diagrams, ForceKind::normal, dim).size());
      EXPECT_GE(value, bottleneck) << "pd" << dim << " frame " << k;
      EXPECT_LE(value, bottleneck * std::pow(points, 1e-3) * (1 + 1e-12)) << "pd" << dim << " frame " << k;
    }
  }

  // fnetctl --format json: one object with equal-length arrays frame, rho, value.
  Process ctl(FNETCTL,
              {"--port", std::to_string(server.port), "query", "--metric", "wasserstein2", "--run", "live", "--dim",
               "0", "--format", "json"},
              tmp.path() / "fnetctl.log");
  ASSERT_EQ(ctl.wait(30s), 0);
  const json q = json::parse(ctl.read_rest());
  ASSERT_EQ(q["frame"].size(), 6u);
  ASSERT_EQ(q["rho"].size(), 6u);
  ASSERT_EQ(q["value"].size(), 6u);
  EXPECT_TRUE(q["value"][0].is_null());
  EXPECT_EQ(q["value"][3].get<double>(), offline.frames[3].distances(Metric::wasserstein2, 0, ForceKind::normal));
  EXPECT_EQ(server.process->stop(), 0);
}

TEST(Service, ServerStartedAfterTheRunStillGetsEveryFrame) {
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {0, 1, 2, 3});
  auto pub = publish(run_dir, "early", 32, tmp.path() / "publish.log", 0, 60, 0);
  // The publisher has written everything (no reader exists yet) before the server starts.
  const auto reported = [&] {
    return fs::exists(tmp.path() / "publish.log") && fs::file_size(tmp.path() / "publish.log") > 0;
  };
  for (int k = 0; k < 300 && !reported(); ++k) std::this_thread::sleep_for(50ms);
  ASSERT_TRUE(reported()) << "publisher never reported";
  ServerProcess server = start_server(tmp.path() / "data", 32, tmp.path() / "server.log");
  const json run = wait_for_frames(server.port, "early", 4);
  EXPECT_EQ(run["frames"], 4);
  EXPECT_EQ(run["announced"], true);
  pub->stop();
}

TEST(Service, KilledServerRestartsAndEndsWithTheCompleteSeriesCountedOnce) {
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {0, 1, 2, 3, 4, 5});
  auto pub = publish(run_dir, "crash", 33, tmp.path() / "publish.log", 3, 120);
  {
    ServerProcess first = start_server(tmp.path() / "data", 33, tmp.path() / "server1.log");
    RpcClient rpc("127.0.0.1", first.port);
    int stored_at_kill = 0;
    for (int k = 0; k < 600 && stored_at_kill < 2; ++k) {  // kill it mid-run, once some frames are stored
      const json runs = rpc.call("runs.list")["runs"];
      if (!runs.empty()) stored_at_kill = runs[0]["frames"].get<int>();
      if (stored_at_kill < 2) std::this_thread::sleep_for(50ms);
    }
    const json served = rpc.call("series.get", {{"run", "crash"}, {"metric", "bottleneck"}});
    first.process->signal(SIGKILL);
    first.process->wait(10s);
    ASSERT_GE(stored_at_kill, 2);
    EXPECT_LT(stored_at_kill, 6) << "the kill came after the whole run: the restart recovers nothing";
    // Nothing reported committed before the kill is lost: every frame served is in the store.
    std::set<std::uint32_t> in_store;
    for (const AnalyzedFrame& f : read_store(store_path(tmp.path() / "data", "crash")).frames)
      in_store.insert(f.header.index);
    for (const json& k : served["frame"]) EXPECT_TRUE(in_store.count(k.get<std::uint32_t>())) << "frame " << k;
  }
  ServerProcess second = start_server(tmp.path() / "data", 33, tmp.path() / "server2.log");
  const json run = wait_for_frames(second.port, "crash", 6);
  EXPECT_EQ(run["frames"], 6);
  EXPECT_EQ(run["rejected"], 0);
  const StoredRun offline = offline_store(run_dir, "crash", tmp.path() / "offline", tmp.path() / "store.log");
  expect_series_match(second.port, "crash", offline);
  // Nothing counted twice: the store holds each frame once.
  const StoredRun stored = read_store(store_path(tmp.path() / "data", "crash"));
  std::set<std::uint32_t> indices;
  for (const AnalyzedFrame& f : stored.frames) EXPECT_TRUE(indices.insert(f.header.index).second) << f.header.index;
  EXPECT_EQ(indices.size(), 6u);
  pub->stop();
}

TEST(Service, RunsKeepTheirLastActivityAndTheNewestRunAcrossRestarts) {
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {0, 1});
  const fs::path data = tmp.path() / "data";
  // Name order is the reverse of activity order, so that neither can pass for the other.
  const StoredRun older = offline_store(run_dir, "b-older", data, tmp.path() / "store1.log");
  std::this_thread::sleep_for(1100ms);
  const StoredRun newer = offline_store(run_dir, "a-newer", data, tmp.path() / "store2.log");
  ASSERT_TRUE(older.last_activity() && newer.last_activity());
  ASSERT_LT(*older.last_activity(), *newer.last_activity());
  std::this_thread::sleep_for(1500ms);
  for (int restart = 0; restart < 2; ++restart) {  // the second start reads the stores the first rewrote
    SCOPED_TRACE(restart);
    ServerProcess server = start_server(data, 39, tmp.path() / ("server" + std::to_string(restart) + ".log"));
    RpcClient rpc("127.0.0.1", server.port);
    const json listed = rpc.call("runs.list");
    ASSERT_EQ(listed["runs"].size(), 2u);
    EXPECT_EQ(rpc.call("run.get")["run"], "a-newer");  // the default run is the newest
    for (const json& r : listed["runs"]) {
      const StoredRun& stored = r["run"] == "a-newer" ? newer : older;
      EXPECT_GE(r["seconds_since_last_frame"].get<double>(), r["run"] == "a-newer" ? 1.5 : 2.6) << r.dump();
      ASSERT_TRUE(r.contains("last_activity")) << r.dump();
      EXPECT_EQ(r["last_activity"].get<double>(), *stored.last_activity()) << r.dump();
    }
    EXPECT_EQ(server.process->stop(), 0);
  }
}

TEST(Service, BadFramesAreRejectedReportedAndTheRunGoesOn) {
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {0, 1, 2, 3, 4}, [](int k, std::vector<std::string>& rows) {
    if (k == 1) rows[5] = "10,11,nan,0.5";      // a NaN force
    if (k == 3) rows[7] = "10,999999,1.0,0.5";  // an index out of range
  });
  ServerProcess server = start_server(tmp.path() / "data", 34, tmp.path() / "server.log");
  auto pub = publish(run_dir, "bad", 34, tmp.path() / "publish.log");
  EXPECT_EQ(pub->wait(120s), 0);
  const json run = wait_for_frames(server.port, "bad", 5);
  EXPECT_EQ(run["frames"], 3);
  EXPECT_EQ(run["rejected"], 2);
  RpcClient rpc("127.0.0.1", server.port);
  const json status = rpc.call("server.status");
  EXPECT_EQ(status["frames"]["rejected"], 2);
  const std::string reasons = status["rejections"].dump();
  EXPECT_NE(reasons.find("run bad frame 1"), std::string::npos) << reasons;
  EXPECT_NE(reasons.find("non-finite"), std::string::npos) << reasons;
  EXPECT_NE(reasons.find("run bad frame 3"), std::string::npos) << reasons;
  EXPECT_NE(reasons.find("out of range"), std::string::npos) << reasons;
  const json series = rpc.call("series.get", {{"run", "bad"}, {"metric", "bottleneck"}});
  EXPECT_EQ(series["frame"], json({0, 2, 4}));
  EXPECT_EQ(series["previous"], json({nullptr, 0, 2}));  // distances skip the rejected frames
}

TEST(Service, OutOfOrderAndDuplicateFramesAreOrderedAndCountedOnce) {
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {0, 1, 2, 3});
  // Published as 0, 2, 1, 3, 2: frame 2 arrives before 1, and twice.
  {
    std::ifstream in(run_dir / "index.csv");
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);) rows.push_back(line);
    std::ofstream out(run_dir / "index.csv");
    out << rows[0] << "\n"
        << rows[1] << "\n"
        << rows[3] << "\n"
        << rows[2] << "\n"
        << rows[4] << "\n"
        << rows[3] << "\n";
  }
  ServerProcess server = start_server(tmp.path() / "data", 38, tmp.path() / "server.log");
  auto pub = publish(run_dir, "shuffled", 38, tmp.path() / "publish.log");
  EXPECT_EQ(pub->wait(120s), 0);
  const json run = wait_for_frames(server.port, "shuffled", 4);
  EXPECT_EQ(run["frames"], 4);
  EXPECT_EQ(run["duplicates"], 1);
  RpcClient rpc("127.0.0.1", server.port);
  const json series = rpc.call("series.get", {{"run", "shuffled"}, {"metric", "wasserstein1"}, {"dim", 1}});
  EXPECT_EQ(series["frame"], json({0, 1, 2, 3}));
  EXPECT_EQ(series["previous"],
            json({nullptr, 0, 1, 2}));  // distances between consecutive frames, whatever the arrival order
  const StoredRun offline = offline_store(lammps_run(tmp.path() / "ordered", {0, 1, 2, 3}), "shuffled",
                                          tmp.path() / "offline", tmp.path() / "store.log");
  expect_series_match(server.port, "shuffled", offline);
}

TEST(Service, TwoRunsStreamingAtOnceAreKeptApart) {
  testing::TempDir tmp;
  const fs::path a = lammps_run(tmp.path() / "a", {0, 1, 2, 3});
  const fs::path b = lammps_run(tmp.path() / "b", {5, 4, 3, 2});
  ServerProcess server = start_server(tmp.path() / "data", 35, tmp.path() / "server.log");
  auto pa = publish(a, "run-a", 35, tmp.path() / "pa.log", 20);
  auto pb = publish(b, "run-b", 35, tmp.path() / "pb.log", 20);
  EXPECT_EQ(pa->wait(120s), 0);
  EXPECT_EQ(pb->wait(120s), 0);
  wait_for_frames(server.port, "run-a", 4);
  wait_for_frames(server.port, "run-b", 4);
  expect_series_match(server.port, "run-a", offline_store(a, "run-a", tmp.path() / "offline", tmp.path() / "sa.log"));
  expect_series_match(server.port, "run-b", offline_store(b, "run-b", tmp.path() / "offline", tmp.path() / "sb.log"));
  // And across runs: frame 0 of b is frame 5 of the LAMMPS run, frame 2 of a is frame 2: distinct.
  RpcClient rpc("127.0.0.1", server.port);
  const json d =
      rpc.call("distance.get",
               {{"run", "run-a"}, {"frame", 3}, {"other_run", "run-b"}, {"other_frame", 2}, {"metric", "bottleneck"}});
  EXPECT_EQ(d["value"].get<double>(), 0.0);  // both are LAMMPS frame 3
  const json e =
      rpc.call("distance.get",
               {{"run", "run-a"}, {"frame", 0}, {"other_run", "run-b"}, {"other_frame", 0}, {"metric", "bottleneck"}});
  EXPECT_GT(e["value"].get<double>(), 0.0);
}

TEST(Service, BadRequestsGetErrorsAndEveryoneElseIsStillServed) {
  testing::TempDir tmp;
  ServerProcess server = start_server(tmp.path() / "data", 36, tmp.path() / "server.log",
                                      {"--threads", "2", "--max-connections", "64", "--max-line-bytes", "65536",
                                       "--max-queued-bytes", "1000000", "--write-timeout", "3"});
  const auto raw = [&](const std::string& text) {
    boost::asio::io_context io;
    boost::asio::ip::tcp::socket s(io);
    s.connect({boost::asio::ip::make_address("127.0.0.1"), server.port});
    boost::system::error_code ec;
    boost::asio::write(s, boost::asio::buffer(text), ec);  // the server may stop reading a huge line
    s.shutdown(boost::asio::ip::tcp::socket::shutdown_send, ec);
    std::string out;
    char buf[4096];
    while (std::size_t n = s.read_some(boost::asio::buffer(buf), ec)) out.append(buf, n);
    return out;
  };
  const auto error_code = [](const std::string& line) { return json::parse(line)["error"]["code"].get<int>(); };
  EXPECT_EQ(error_code(raw("{not json\n")), -32700);
  EXPECT_EQ(error_code(raw(R"({"jsonrpc":"2.0","id":1,"method":"no.such"})"
                           "\n")),
            -32601);
  EXPECT_EQ(error_code(raw(R"({"jsonrpc":"2.0","id":1,"method":"series.get","params":{"metric":42}})"
                           "\n")),
            -32602);
  EXPECT_EQ(error_code(raw(R"({"jsonrpc":"2.0","id":1,"method":"diagram.get","params":{"frame":"x"}})"
                           "\n")),
            -32602);
  EXPECT_EQ(error_code(raw(R"({"jsonrpc":"1.0","id":1,"method":"runs.list"})"
                           "\n")),
            -32600);
  EXPECT_EQ(error_code(raw(R"({"jsonrpc":"2.0","id":1,"method":"run.get","params":{"run":"nope"}})"
                           "\n")),
            -32001);
  // A 10 MB line: an error, then the connection closes.
  EXPECT_EQ(error_code(raw(std::string(10 << 20, 'x') + "\n")), -32600);

  // Hundreds of connections at once: beyond the limit they are refused with -32004.
  boost::asio::io_context io;
  std::vector<std::unique_ptr<boost::asio::ip::tcp::socket>> crowd;
  for (int k = 0; k < 300; ++k) {
    crowd.push_back(std::make_unique<boost::asio::ip::tcp::socket>(io));
    boost::system::error_code ec;
    crowd.back()->connect({boost::asio::ip::make_address("127.0.0.1"), server.port}, ec);
  }
  std::size_t refused = 0;
  for (auto& s : crowd) {
    s->non_blocking(true);
    char buf[256];
    boost::system::error_code ec;
    for (int k = 0; k < 20; ++k) {
      const std::size_t n = s->read_some(boost::asio::buffer(buf), ec);
      if (n > 0 && std::string(buf, n).find("-32004") != std::string::npos) ++refused;
      if (ec != boost::asio::error::would_block) break;
      if (refused) break;
      std::this_thread::sleep_for(1ms);
    }
    if (refused >= 200) break;
  }
  EXPECT_GE(refused, 200u);
  crowd.clear();

  // A client that never reads: it asks for much more than the output bound, is not read past it,
  // and is dropped once its output has not moved for --write-timeout.
  boost::asio::ip::tcp::socket hog(io);
  hog.connect({boost::asio::ip::make_address("127.0.0.1"), server.port});
  const std::string request = R"({"jsonrpc":"2.0","id":1,"method":"server.status"})"
                              "\n";
  std::string flood;
  for (int k = 0; k < 20000; ++k) flood += request;
  boost::system::error_code ec;
  boost::asio::write(hog, boost::asio::buffer(flood), ec);

  // Everyone else is still served, and the hog is dropped: one client of ours polls until it is
  // the only connection left (the server sees the crowd's and the hog's ends asynchronously, and
  // slowly in a sanitizer build, so a deadline rather than one look). Until the server has seen
  // the crowd's ends, a new connection may still be refused for the limit: it is tried again.
  int connections = 0, refusals = 0;
  std::optional<RpcClient> rpc;
  for (int k = 0; k < 600 && connections != 1; ++k) {
    try {
      if (!rpc) rpc.emplace("127.0.0.1", server.port);
      connections = rpc->call("server.status")["connections"].get<int>();
    } catch (const std::exception&) {
      rpc.reset();
      ++refusals;
    }
    if (connections != 1) std::this_thread::sleep_for(50ms);
  }
  EXPECT_EQ(connections, 1) << "the non-reading client was not dropped (" << refusals << " tries refused)";
  EXPECT_EQ(server.process->stop(), 0);
}

// Each connection holds at most --max-subscriptions of each kind (series, ensemble); an id is
// ended only by the connection and the kind of unsubscribe that made it, and a connection that
// closes ends all of its own (proto/api.md, series.subscribe and ensemble.subscribe).
TEST(Service, SubscriptionsAreEachConnectionsOwnUpToTheLimitOfEachKind) {
  testing::TempDir tmp;
  const fs::path data = tmp.path() / "data";
  ASSERT_EQ(store_run(lammps_run(tmp.path() / "csv", {0, 1, 2}), "demo", data, tmp.path() / "store.log", "demo-ens"),
            0);
  ServerProcess server =
      start_server(data, 58, tmp.path() / "server.log", {"--threads", "2", "--max-subscriptions", "2"});
  const json curve = {{"ensemble", "demo-ens"}, {"metric", "bottleneck"}};
  const auto error_of = [](const json& reply, int code, const std::string& message) {
    SCOPED_TRACE(reply.dump());
    ASSERT_TRUE(reply.contains("error"));
    EXPECT_EQ(reply["error"]["code"], code);
    EXPECT_EQ(reply["error"]["message"], message);
    if (code == -32602) {
      EXPECT_EQ(reply["error"]["data"]["parameter"], "subscription");
    }
  };
  const auto not_here = [](const std::string& kind, std::uint64_t id) {
    return "parameter 'subscription': no " + kind + " " + std::to_string(id) + " on this connection";
  };
  LineConnection other(server.port);
  {
    LineConnection mine(server.port);
    std::vector<std::uint64_t> series, curves;
    for (int k = 0; k < 2; ++k) {
      series.push_back(mine.call("series.subscribe", {{"since", 2}})["result"]["subscription"].get<std::uint64_t>());
      curves.push_back(mine.call("ensemble.subscribe", curve)["result"]["subscription"].get<std::uint64_t>());
    }
    error_of(mine.call("series.subscribe", {{"since", 2}}), -32003, "at most 2 subscriptions per connection");
    error_of(mine.call("ensemble.subscribe", curve), -32003, "at most 2 ensemble subscriptions per connection");
    EXPECT_TRUE(other.call("series.subscribe", {{"since", 2}})["result"].contains("subscription"))
        << "another connection has room of its own";

    error_of(other.call("series.unsubscribe", {{"subscription", series[0]}}), -32602,
             not_here("subscription", series[0]));
    error_of(mine.call("series.unsubscribe", {{"subscription", curves[0]}}), -32602,
             not_here("subscription", curves[0]));
    error_of(mine.call("ensemble.unsubscribe", {{"subscription", series[0]}}), -32602,
             not_here("ensemble subscription", series[0]));
    EXPECT_EQ(mine.call("series.unsubscribe", {{"subscription", series[0]}})["result"]["unsubscribed"], series[0]);
    EXPECT_EQ(mine.call("ensemble.unsubscribe", {{"subscription", curves[0]}})["result"]["unsubscribed"], curves[0]);
    error_of(mine.call("series.unsubscribe", {{"subscription", series[0]}}), -32602,
             not_here("subscription", series[0]));
    EXPECT_TRUE(mine.call("series.subscribe", {{"since", 2}})["result"].contains("subscription"))
        << "an unsubscribe makes room";
    EXPECT_EQ(other.call("server.status", json::object())["result"]["subscriptions"], 4);
  }
  // The closed connection's three end with it; the other connection's one stays.
  json subscriptions;
  for (int k = 0; k < 100; ++k) {
    subscriptions = other.call("server.status", json::object())["result"]["subscriptions"];
    if (subscriptions == 1) break;
    std::this_thread::sleep_for(50ms);
  }
  EXPECT_EQ(subscriptions, 1);
  EXPECT_EQ(server.process->stop(), 0);
}

TEST(Service, SubscriberGetsLivePointsAndWhatItMissedAfterReconnecting) {
  testing::TempDir tmp;
  const fs::path run_dir = lammps_run(tmp.path() / "csv", {0, 1, 2, 3, 4});
  ServerProcess server = start_server(tmp.path() / "data", 37, tmp.path() / "server.log");
  RpcClient watcher("127.0.0.1", server.port);
  std::vector<std::uint32_t> seen;
  auto pub = publish(run_dir, "live", 37, tmp.path() / "publish.log", 4);
  // The run exists once its first frame or announcement arrives.
  for (int k = 0; k < 600; ++k) {
    try {
      watcher.call("series.subscribe", {{"run", "live"}});
      break;
    } catch (const client::CallError&) {
      std::this_thread::sleep_for(20ms);
    }
  }
  while (seen.size() < 2) {
    const auto n = watcher.next_notification(30s);
    ASSERT_TRUE(n) << "no live point";
    seen.push_back((*n)["params"]["frame"].get<std::uint32_t>());
  }
  // Reconnect with the last frame seen: exactly the rest follows, in order, once each.
  RpcClient again("127.0.0.1", server.port);
  again.call("series.subscribe", {{"run", "live"}, {"since", seen.back()}});
  while (seen.size() < 5) {
    const auto n = again.next_notification(60s);
    ASSERT_TRUE(n) << "missing points after reconnecting";
    seen.push_back((*n)["params"]["frame"].get<std::uint32_t>());
  }
  EXPECT_EQ(seen, (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_FALSE(again.next_notification(500ms)) << "a point was sent twice";
  pub->stop();
}

// A backlog many times the connection's output bound reaches a client that reads, whole and in
// order: the points are sent as the client reads them, never queued in one go.
TEST(Service, ASubscriberThatReadsGetsABacklogFarPastItsOutputBound) {
  testing::TempDir tmp;
  constexpr int kFrames = 200;
  std::vector<int> source;
  for (int k = 0; k < kFrames; ++k) source.push_back(k % 11);
  const fs::path run_dir = lammps_run(tmp.path() / "csv", source);
  ASSERT_EQ(store_run(run_dir, "long", tmp.path() / "data", tmp.path() / "store.log"), 0);
  ServerProcess server =
      start_server(tmp.path() / "data", 226, tmp.path() / "server.log", {"--max-queued-bytes", "32768"});
  LineConnection c(server.port);
  const json subscribed = c.call("series.subscribe", {{"run", "long"}});
  ASSERT_TRUE(subscribed.contains("result")) << subscribed.dump();
  std::vector<std::uint32_t> frames;
  for (const json& n : c.notifications) frames.push_back(n["params"]["frame"]);
  while (frames.size() < static_cast<std::size_t>(kFrames)) {
    const auto n = c.next(30s);
    ASSERT_TRUE(n) << "the backlog stopped after " << frames.size() << " points";
    ASSERT_EQ((*n)["method"], "series.point") << n->dump();
    frames.push_back((*n)["params"]["frame"]);
  }
  for (int k = 0; k < kFrames; ++k) EXPECT_EQ(frames[k], static_cast<std::uint32_t>(k));
  EXPECT_TRUE(c.call("runs.list", json::object()).contains("result")) << "the connection did not go on";
}

TEST(Service, BrokenDdsConfigurationFailsAtStartNamingIt) {
  testing::TempDir tmp;
  const fs::path broken = tmp.path() / "broken.xml";
  std::ofstream(broken) << "<CycloneDDS><Domain><General><NoSuchSetting>1</NoSuchSetting></General></Domain>";
  for (const std::string& uri : {"file://" + broken.string(), "file://" + (tmp.path() / "absent.xml").string()}) {
    const fs::path log = tmp.path() / "server.log";
    fs::remove(log);
    Process server(FNET_SERVER, {"--data-dir", (tmp.path() / "data").string(), "--port", "0", "--domain", "51"}, log,
                   {{"CYCLONEDDS_URI", uri}});
    const auto rc = server.wait(60s);
    ASSERT_TRUE(rc) << "fnet-server kept running with CYCLONEDDS_URI=" << uri;
    EXPECT_NE(*rc, 0);
    const std::string text = read_file(log);
    EXPECT_NE(text.find("DDS"), std::string::npos) << text;
    EXPECT_NE(text.find(uri), std::string::npos) << "the message does not name CYCLONEDDS_URI: " << text;
    EXPECT_EQ(server.read_rest().find("listening"), std::string::npos) << "it announced it was serving";
  }
}

TEST(Service, StatusReportsTheIngestStateAndNoDeadCounters) {
  testing::TempDir tmp;
  ServerProcess server = start_server(tmp.path() / "data", 52, tmp.path() / "server.log");
  RpcClient rpc("127.0.0.1", server.port);
  const json status = rpc.call("server.status");
  EXPECT_EQ(status["ingest"], "running");
  EXPECT_FALSE(status["lag"].contains("ingest_queue")) << "a counter that is always 0";
  EXPECT_EQ(server.process->stop(), 0);
}

TEST(Service, TakenPortStopsTheServerNamingTheAddress) {
  boost::asio::io_context io;
  boost::asio::ip::tcp::acceptor occupant(io, {boost::asio::ip::make_address("127.0.0.1"), 0});
  const unsigned short port = occupant.local_endpoint().port();
  testing::TempDir tmp;
  Process server(FNET_SERVER,
                 {"--data-dir", (tmp.path() / "data").string(), "--port", std::to_string(port), "--domain", "51"},
                 tmp.path() / "server.log", dds_environment());
  const auto rc = server.wait(60s);
  ASSERT_TRUE(rc) << "fnet-server kept running on a taken port";
  EXPECT_NE(*rc, 0);
  const std::string text = read_file(tmp.path() / "server.log");
  EXPECT_NE(text.find("127.0.0.1:" + std::to_string(port)), std::string::npos) << text;
  EXPECT_NE(text.find("in use"), std::string::npos) << text;
}

TEST(Service, BindAddressThatIsNoAddressIsAUsageError) {
  testing::TempDir tmp;
  Process server(FNET_SERVER, {"--data-dir", (tmp.path() / "data").string(), "--bind", "localhost:7707"},
                 tmp.path() / "server.log", dds_environment());
  EXPECT_EQ(server.wait(60s), 2);
  const std::string text = read_file(tmp.path() / "server.log");
  EXPECT_NE(text.find("--bind 'localhost:7707'"), std::string::npos) << text;
  // A word that is no option's value (an unquoted pattern, a typo) is refused, not dropped.
  Process stray(FNET_SERVER, {"--data-dir", (tmp.path() / "data").string(), "--port", "0", "stray"},
                tmp.path() / "stray.log", dds_environment());
  EXPECT_EQ(stray.wait(60s), 2);
  const std::string said = read_file(tmp.path() / "stray.log");
  EXPECT_NE(said.find("unexpected argument 'stray'"), std::string::npos) << said;
}

// proto/api.md's Limits table against the server: every flag it names is an option of fnet-server.
TEST(Service, TheLimitsTableNamesTheServersOptions) {
  testing::TempDir tmp;
  Process help(FNET_SERVER, {"--help"}, tmp.path() / "help.log", dds_environment());
  const std::string options = help.read_rest();
  EXPECT_EQ(help.wait(60s), 0);
  const std::string doc = read_file(fs::path(FNET_SOURCE_DIR) / "proto" / "api.md");
  const std::size_t begin = doc.find("## Limits\n"), end = doc.find("\n## ", begin + 1);
  ASSERT_NE(begin, std::string::npos);
  const std::string table = doc.substr(begin, end - begin);
  const std::regex flag("`(--[a-z-]+)`");
  std::set<std::string> flags;
  for (auto it = std::sregex_iterator(table.begin(), table.end(), flag); it != std::sregex_iterator(); ++it)
    flags.insert((*it)[1]);
  EXPECT_GE(flags.size(), 9u);
  for (const std::string& f : flags) EXPECT_NE(options.find("  " + f + " "), std::string::npos) << f << " is no option";
}

// A three-frame run "demo" of ensemble "demo-ens", served: what proto/api.md's examples are written against.
struct DemoRun {
  testing::TempDir tmp;
  ServerProcess server;
  explicit DemoRun(int domain) {
    const fs::path run_dir = lammps_run(tmp.path() / "csv", {0, 1, 2});
    server = start_server(tmp.path() / "data", domain, tmp.path() / "server.log");
    auto pub = publish(run_dir, "demo", domain, tmp.path() / "publish.log", 0, 0, 30, "demo-ens");
    EXPECT_EQ(pub->wait(120s), 0);
    wait_for_frames(server.port, "demo", 3);
  }
};

void expect_invalid_param(const json& reply, const std::string& parameter, const std::string& what) {
  SCOPED_TRACE(what + ": " + reply.dump());
  ASSERT_TRUE(reply.contains("error"));
  EXPECT_EQ(reply["error"]["code"], -32602);
  const std::string message = reply["error"]["message"];
  EXPECT_NE(message.find("'" + parameter + "'"), std::string::npos) << "the message does not name " << parameter;
  EXPECT_EQ(message.find("json.exception"), std::string::npos) << "raw JSON-library text";
  EXPECT_EQ(reply["error"]["data"]["parameter"], parameter);
}

TEST(Service, ApiRejectsUnknownParametersBadRangesAndTypesNamingThem) {
  DemoRun demo(54);
  LineConnection c(demo.server.port);
  // A typo is not a silently applied default.
  expect_invalid_param(c.call("series.get", {{"run", "demo"}, {"metric", "bottleneck"}, {"dimension", 1}}), "dimension",
                       "typo");
  expect_invalid_param(c.call("runs.list", {{"verbose", true}}), "verbose", "a method that takes no params");
  expect_invalid_param(c.call("series.get", {{"run", "demo"}, {"metric", "bottleneck"}, {"from", 2}, {"to", 1}}),
                       "from", "from > to");
  EXPECT_EQ(
      c.call("series.get", {{"run", "demo"}, {"metric", "bottleneck"}, {"from", 1}, {"to", 1}})["result"]["frame"],
      json({1}));
  expect_invalid_param(c.call("series.get", {{"run", "demo"}, {"metric", "bottleneck"}, {"q", 3}}), "q",
                       "bottleneck is q = infinity");
  expect_invalid_param(c.call("series.get", {{"run", "demo"}, {"metric", "wasserstein2"}, {"q", 3}}), "q",
                       "q contradicts the metric");
  expect_invalid_param(c.call("series.get", {{"run", "demo"}, {"metric", "wasserstein"}, {"q", 0.5}}), "q", "q < 1");
  expect_invalid_param(c.call("series.get", {{"run", "demo"}, {"metric", "manhattan"}}), "metric", "unknown metric");
  expect_invalid_param(c.call("series.get", {{"run", "demo"}}), "metric", "missing metric");
  // 2^32 once read as an int was dim 0.
  expect_invalid_param(c.call("series.get", {{"run", "demo"}, {"metric", "bottleneck"}, {"dim", 4294967296LL}}), "dim",
                       "dim 2^32");
  // Every wrong type is named, with the type expected, never with the JSON library's words.
  const std::vector<std::tuple<std::string, json, std::string>> wrong = {
      {"series.get", {{"metric", 42}}, "metric"},
      {"series.get", {{"metric", "wasserstein"}, {"q", "2"}}, "q"},
      {"series.get", {{"metric", "bottleneck"}, {"dim", "1"}}, "dim"},
      {"series.get", {{"metric", "bottleneck"}, {"dim", 0.5}}, "dim"},
      {"series.get", {{"metric", "bottleneck"}, {"force", 1}}, "force"},
      {"series.get", {{"metric", "bottleneck"}, {"force", "shear"}}, "force"},
      {"series.get", {{"metric", "bottleneck"}, {"essential", "maybe"}}, "essential"},
      {"series.get", {{"metric", "bottleneck"}, {"from", -1}}, "from"},
      {"series.get", {{"metric", "bottleneck"}, {"to", 1.5}}, "to"},
      {"series.get", {{"metric", "bottleneck"}, {"run", 7}}, "run"},
      {"diagram.get", {{"frame", "x"}}, "frame"},
      {"diagram.get", {{"frame", 18446744073709551615ULL}}, "frame"},
      {"diagram.get", {{"frame", {1}}}, "frame"},
      {"distance.get", {{"frame", 0}, {"metric", "bottleneck"}}, "other_frame"},
      {"distance.get", {{"frame", 0}, {"other_frame", 1}, {"metric", "bottleneck"}, {"delta", -1}}, "delta"},
      {"distance.get", {{"frame", 0}, {"other_frame", 1}, {"metric", "bottleneck"}, {"delta", "0"}}, "delta"},
      {"series.subscribe", {{"since", true}}, "since"},
      {"series.unsubscribe", json::object(), "subscription"},
      {"series.unsubscribe", {{"subscription", 99}}, "subscription"},
  };
  for (const auto& [method, params, parameter] : wrong)
    expect_invalid_param(c.call(method, params), parameter, method + " " + params.dump());
  // A line that is not JSON: the byte, not the library's message.
  c.send("{not json");
  const auto parse = c.next();
  ASSERT_TRUE(parse);
  EXPECT_EQ((*parse)["error"]["code"], -32700);
  EXPECT_EQ((*parse)["error"]["message"].get<std::string>().find("json.exception"), std::string::npos) << *parse;
  // Every unknown run is named in data.run, whichever method met it.
  const std::vector<std::pair<std::string, json>> unknown = {
      {"run.get", {{"run", "nope"}}},
      {"series.get", {{"run", "nope"}, {"metric", "bottleneck"}}},
      {"diagram.get", {{"run", "nope"}, {"frame", 0}}},
      {"distance.get",
       {{"run", "demo"}, {"other_run", "nope"}, {"frame", 0}, {"other_frame", 0}, {"metric", "bottleneck"}}},
      {"series.subscribe", {{"run", "nope"}}},
  };
  for (const auto& [method, params] : unknown) {
    const json reply = c.call(method, params);
    EXPECT_EQ(reply["error"]["code"], -32001) << method << " " << reply;
    EXPECT_EQ(reply["error"]["data"]["run"], "nope") << method << " " << reply;
  }
  const json frame =
      c.call("distance.get", {{"run", "demo"}, {"frame", 0}, {"other_frame", 9}, {"metric", "bottleneck"}});
  EXPECT_EQ(frame["error"]["code"], -32002) << frame;
  EXPECT_EQ(frame["error"]["data"], json({{"run", "demo"}, {"frame", 9}})) << frame;
}

// Where `got` differs in shape from `doc` (same keys, same JSON types; each element of an array
// shaped as some element of the document's), or nullopt.
std::optional<std::string> shape_difference(const json& doc, const json& got, const std::string& path) {
  const auto kind = [](const json& v) { return v.is_number() ? std::string("number") : std::string(v.type_name()); };
  if (kind(doc) != kind(got)) return path + ": " + kind(got) + " where the document has " + kind(doc);
  if (doc.is_object()) {
    for (const auto& [key, value] : doc.items())
      if (!got.contains(key)) return path + ": no '" + key + "'";
    for (const auto& [key, value] : got.items()) {
      if (!doc.contains(key)) return path + ": '" + key + "' is not in the document";
      if (auto d = shape_difference(doc[key], value, path + "." + key)) return d;
    }
  }
  if (doc.is_array() && !doc.empty()) {
    if (got.empty()) return path + ": empty where the document has elements";
    for (std::size_t k = 0; k < got.size(); ++k) {
      std::optional<std::string> first;
      bool matched = false;
      for (const json& d : doc) {
        auto diff = shape_difference(d, got[k], path + "[" + std::to_string(k) + "]");
        if (!diff) matched = true;
        if (!first) first = diff;
      }
      if (!matched) return first;
    }
  }
  return std::nullopt;
}

// Where `got` differs from `doc` in value (numbers within 1e-5 relative: the document rounds them;
// arrays of the same length; "seconds" not compared), or nullopt.
std::optional<std::string> value_difference(const json& doc, const json& got, const std::string& path) {
  if (doc.is_number() && got.is_number()) {
    const double a = doc.get<double>(), b = got.get<double>();
    if (std::abs(a - b) <= 1e-5 * std::max(std::abs(a), std::abs(b)) + 1e-9) return std::nullopt;
    return path + ": " + got.dump() + " where the document has " + doc.dump();
  }
  if (doc.type() != got.type()) return path + ": " + got.dump() + " where the document has " + doc.dump();
  if (doc.is_object()) {
    for (const auto& [key, value] : got.items())
      if (!doc.contains(key)) return path + ": '" + key + "' is not in the document";
    for (const auto& [key, value] : doc.items()) {
      if (!got.contains(key)) return path + ": no '" + key + "'";
      if (key == "seconds") continue;
      if (auto d = value_difference(value, got[key], path + "." + key)) return d;
    }
    return std::nullopt;
  }
  if (doc.is_array()) {
    if (doc.size() != got.size())
      return path + ": " + std::to_string(got.size()) + " elements, the document " + std::to_string(doc.size());
    for (std::size_t k = 0; k < doc.size(); ++k)
      if (auto d = value_difference(doc[k], got[k], path + "[" + std::to_string(k) + "]")) return d;
    return std::nullopt;
  }
  if (doc != got) return path + ": " + got.dump() + " where the document has " + doc.dump();
  return std::nullopt;
}

// proto/api.md is the API's contract: each method's Params line lists exactly what the server
// accepts, and each example ("→" request, "←" replies) gives replies of the shapes it shows. The
// examples of run "demo3d", a 3D run made here, give the values the document shows.
TEST(Service, ApiDocumentListsWhatTheServerAcceptsAndItsExamplesRun) {
  DemoRun demo(55);
  const std::string doc = read_file(fs::path(FNET_SOURCE_DIR) / "proto" / "api.md");
  LineConnection c(demo.server.port);

  // Params: every documented method exists and accepts exactly the names its section lists.
  // (Split by hand: std::regex recurses per character and would overflow on a long section.)
  std::size_t methods = 0;
  const std::string heading = "\n### `";
  for (std::size_t at = doc.find(heading); at != std::string::npos;) {
    const std::size_t name_end = doc.find('`', at + heading.size());
    const std::string method = doc.substr(at + heading.size(), name_end - at - heading.size());
    const std::size_t next = doc.find("\n#", name_end);
    const std::string body = doc.substr(name_end, next == std::string::npos ? std::string::npos : next - name_end);
    at = doc.find(heading, name_end);
    const auto start = body.find("Params:"), end = body.find("Result:");
    ASSERT_NE(start, std::string::npos) << method << " has no Params";
    ASSERT_NE(end, std::string::npos) << method << " has no Result";
    const std::string params = body.substr(start, end - start);
    std::set<std::string> documented;
    const std::regex name("`([a-z_]+)`");
    for (auto n = std::sregex_iterator(params.begin(), params.end(), name); n != std::sregex_iterator(); ++n)
      documented.insert((*n)[1]);
    const json reply = c.call(method, {{"no_such_parameter", 1}});
    ASSERT_TRUE(reply.contains("error")) << method << ": " << reply;
    ASSERT_EQ(reply["error"]["code"], -32602) << method << ": " << reply;
    const std::vector<std::string> accepted = reply["error"]["data"]["accepted"];
    EXPECT_EQ(documented, std::set<std::string>(accepted.begin(), accepted.end())) << method;
    ++methods;
  }
  EXPECT_EQ(methods, 15u) << "methods documented";

  // Examples: sent in order on one connection (a subscription and its unsubscription share it).
  std::istringstream lines(doc);
  std::vector<std::pair<std::string, std::vector<json>>> examples;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("→ ", 0) == 0) examples.push_back({line.substr(std::string("→ ").size()), {}});
    if (line.rfind("← ", 0) == 0) {
      ASSERT_FALSE(examples.empty()) << line;
      examples.back().second.push_back(json::parse(line.substr(std::string("← ").size())));
    }
  }
  ASSERT_GE(examples.size(), 8u);
  // Run "demo3d" on a server of its own (DDS domain 203), started when the examples reach it: 108
  // spheres of an FCC packing, frame 1 with the forces of 20 contacts changed in cell (layer 1,
  // row 0, col 1) of a 2 x 2 x 2 grid.
  ServerProcess server_3d;
  std::unique_ptr<LineConnection> c_3d;
  for (const auto& [request, expected] : examples) {
    SCOPED_TRACE(request);
    ASSERT_FALSE(expected.empty()) << "an example without its reply";
    const json sent = json::parse(request);
    const bool three_d = sent.contains("params") && sent["params"].value("run", "") == "demo3d";
    if (three_d && !c_3d) {
      server_3d = start_server(demo.tmp.path() / "data-3d", 203, demo.tmp.path() / "server-3d.log");
      const Planted3D fcc = plant_in_cell({.cells = 3, .k = 2, .layer = 1, .row = 0, .col = 1});
      ASSERT_EQ(publish_run_file(write_run_file_3d(demo.tmp.path() / "demo3d.run.h5", "demo3d", fcc), 203,
                                 demo.tmp.path() / "publish-3d.log"),
                0);
      wait_for_frames(server_3d.port, "demo3d", 3);
      c_3d = std::make_unique<LineConnection>(server_3d.port);
    }
    LineConnection& to = three_d ? *c_3d : c;
    to.notifications.clear();
    to.send(request);
    const json reply = to.reply(sent["id"]);
    for (const json& e : expected) {
      if (e.contains("id")) {
        if (auto d = shape_difference(e, reply, "reply")) ADD_FAILURE() << *d << "\n  got " << reply;
        if (auto d = three_d ? value_difference(e, reply, "reply") : std::nullopt)
          ADD_FAILURE() << *d << "\n  got " << reply;
        if (e.contains("error")) {
          EXPECT_EQ(reply["error"]["code"], e["error"]["code"]);
        }
        continue;
      }
      // A notification: it may come before or after the reply.
      while (std::none_of(to.notifications.begin(), to.notifications.end(),
                          [&](const json& n) { return n["method"] == e["method"]; })) {
        const auto n = to.next(10s);
        ASSERT_TRUE(n) << "no " << e["method"] << " notification";
        to.notifications.push_back(*n);
      }
      for (const json& n : to.notifications)
        if (n["method"] == e["method"]) {
          if (auto d = shape_difference(e, n, "notification")) ADD_FAILURE() << *d << "\n  got " << n;
        }
    }
  }
}

}  // namespace
}  // namespace fnet::e2e
