// blocks.get end to end: a real LAMMPS frame with a change planted in one corner, published over
// DDS to a real fnet-server, located by the cell distances; the same answer after a restart, and a
// clear error for a frame stored before the store kept networks.
#include "common/analysis/blocks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "client/rpc/rpc_client.hpp"
#include "common/analysis/explain.hpp"
#include "common/codec/explain_json.hpp"
#include "tests/e2e/process.hpp"
#include "tests/e2e/service_process.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

namespace fs = std::filesystem;
using client::CallError;
using client::json;
using client::RpcClient;
using namespace std::chrono_literals;

constexpr int kDomain = 83;  // CONTRIBUTING.md: blocks 83-86 (84: the fnetctl test)

// The run's frames: 0 the LAMMPS frame, 1 the same with the forces of the 20 contacts nearest
// the top-left corner of its domain multiplied by 3, 2 the LAMMPS frame again. Top-left (row 1,
// col 0) rather than a corner on the diagonal, so that rows and columns cannot be swapped unseen.
struct PlantedRun {
  Frame original, planted;
  std::vector<std::size_t> strengthened;
};

PlantedRun plant(const Frame& f) {
  PlantedRun out{f, f, {}};
  const BlockDomain d = block_domain(f);
  const double cx = d.x_lo + (d.x_hi - d.x_lo) / 8, cy = d.y_hi - (d.y_hi - d.y_lo) / 8;
  std::vector<std::pair<double, std::size_t>> by_distance;
  for (std::size_t n = 0; n < f.contacts.size(); ++n) {
    const Particle& a = f.particles[f.contacts[n].i];
    by_distance.push_back({std::hypot(a.x - cx, a.y - cy), n});
  }
  std::sort(by_distance.begin(), by_distance.end());
  for (std::size_t k = 0; k < 20; ++k) {
    Contact& c = out.planted.contacts[by_distance[k].second];
    c.fn *= 3, c.ft *= 3;
    out.strengthened.push_back(by_distance[k].second);
  }
  return out;
}

void write_frame_csv(const fs::path& dir, int index, const Frame& f) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%04d_particles.csv", index);
  std::ofstream p(dir / name);
  p.precision(17);
  p << "id,x,y,r\n";
  for (std::size_t g = 0; g < f.particles.size(); ++g)
    p << g << "," << f.particles[g].x << "," << f.particles[g].y << "," << f.particles[g].r << "\n";
  std::snprintf(name, sizeof name, "frame_%04d_contacts.csv", index);
  std::ofstream c(dir / name);
  c.precision(17);
  c << "i,j,fn,ft\n";
  for (const Contact& k : f.contacts) c << k.i << "," << k.j << "," << k.fn << "," << k.ft << "\n";
}

fs::path write_run(const fs::path& dir, const PlantedRun& run) {
  fs::create_directories(dir);
  std::ofstream index(dir / "index.csv");
  index << "frame,step,rho,Z\n";
  const Frame* frames[] = {&run.original, &run.planted, &run.original};
  for (int k = 0; k < 3; ++k) {
    write_frame_csv(dir, k, *frames[k]);
    index << k << "," << 1000 * k << ",0.9,4.0\n";
  }
  return dir;
}

json blocks(RpcClient& rpc, std::uint32_t frame, std::uint32_t other, const std::string& metric, int dim) {
  return rpc.call("blocks.get", {{"run", "planted"},
                                 {"frame", frame},
                                 {"other_frame", other},
                                 {"k", 2},
                                 {"metric", metric},
                                 {"dim", dim},
                                 {"force", "normal"}});
}

json without_time(json reply) {
  reply.erase("seconds");
  return reply;
}

int error_code(RpcClient& rpc, const std::string& method, const json& params, json* data = nullptr,
               std::string* message = nullptr) {
  try {
    rpc.call(method, params);
  } catch (const CallError& e) {
    if (data) *data = e.data();
    if (message) *message = e.what();
    return e.code();
  }
  return 0;
}

TEST(BlocksService, ThePlantedCornerIsTheLargestBlockAndAnUnchangedFrameIsZeroAlsoAfterARestart) {
  testing::TempDir tmp;
  const PlantedRun run = plant(testing::lammps_frame(10));
  const fs::path csv = write_run(tmp.path() / "csv", run);
  const fs::path data = tmp.path() / "data";
  // The planted contacts are all in the top-left cell, as the library assigns them.
  const auto cells = split_into_blocks(run.original, 2);
  for (const std::size_t n : run.strengthened)
    ASSERT_EQ(std::count(cells[2].contacts.begin(), cells[2].contacts.end(), n), 1) << "contact " << n;
  ASSERT_EQ(cells[2].row, 1);
  ASSERT_EQ(cells[2].col, 0);

  std::map<std::string, json> answers;
  {
    ServerProcess server = start_server(data, kDomain, tmp.path() / "server.log");
    auto pub = publish(csv, "planted", kDomain, tmp.path() / "publish.log");
    ASSERT_EQ(pub->wait(120s), 0) << "see " << tmp.path() / "publish.log";
    wait_for_frames(server.port, "planted", 3);
    RpcClient rpc("127.0.0.1", server.port);
    for (const std::string metric : {"bottleneck", "wasserstein2"})
      for (const int dim : {0, 1}) {
        SCOPED_TRACE(metric + " dim " + std::to_string(dim));
        const json changed = blocks(rpc, 0, 1, metric, dim);
        EXPECT_EQ(changed["largest"]["row"], 1) << changed.dump();
        EXPECT_EQ(changed["largest"]["col"], 0) << changed.dump();
        ASSERT_EQ(changed["cells"].size(), 4u);
        // The same cell distances as the library computes from the frames themselves.
        const auto expected =
            block_distances(split_into_blocks(run.original, 2), split_into_blocks(run.planted, 2),
                            metric == "bottleneck" ? DistanceMetric::bottleneck() : DistanceMetric::wasserstein(2), dim,
                            ForceKind::normal);
        for (std::size_t c = 0; c < 4; ++c) {
          const json& cell = changed["cells"][c];
          EXPECT_EQ(cell["value"].get<double>(), expected[c].distance.value) << c;
          EXPECT_EQ(cell["contacts"][0], cells[c].contacts.size());
          if (c != 2) {
            EXPECT_EQ(cell["value"].get<double>(), 0.0) << "an unchanged cell, " << cell.dump();
          }
        }
        EXPECT_GT(changed["largest"]["value"].get<double>(), 0);
        for (const auto& [a, b] : {std::pair{0u, 2u}, std::pair{2u, 2u}}) {
          const json same = blocks(rpc, a, b, metric, dim);
          for (const json& cell : same["cells"]) EXPECT_EQ(cell["value"].get<double>(), 0.0) << same.dump();
        }
        answers[metric + std::to_string(dim)] = without_time(changed);
      }
    // Bad requests are refused by name before any work.
    json data_out;
    EXPECT_EQ(error_code(rpc, "blocks.get",
                         {{"run", "planted"}, {"frame", 0}, {"other_frame", 1}, {"k", 17}, {"metric", "bottleneck"}},
                         &data_out),
              -32602);
    EXPECT_EQ(data_out["parameter"], "k");
    EXPECT_EQ(error_code(rpc, "blocks.get",
                         {{"run", "planted"}, {"frame", 0}, {"other_frame", 1}, {"k", 0}, {"metric", "bottleneck"}},
                         &data_out),
              -32602);
    EXPECT_EQ(
        error_code(rpc, "blocks.get", {{"run", "planted"}, {"frame", 0}, {"other_frame", 9}, {"metric", "bottleneck"}}),
        -32002);
    server.process->stop();
  }
  // A store of the first schema (written before networks were kept) next to the run's.
  fs::copy_file(fs::path(FNET_TEST_DATA) / "store-v1" / "legacy-v1.h5", data / "legacy-v1.h5");
  ServerProcess again = start_server(data, kDomain, tmp.path() / "server2.log");
  RpcClient rpc("127.0.0.1", again.port);
  for (const std::string metric : {"bottleneck", "wasserstein2"})
    for (const int dim : {0, 1})
      EXPECT_EQ(without_time(blocks(rpc, 0, 1, metric, dim)), answers[metric + std::to_string(dim)])
          << metric << " dim " << dim;
  json data_out;
  std::string message;
  EXPECT_EQ(
      error_code(rpc, "blocks.get", {{"run", "legacy-v1"}, {"frame", 0}, {"other_frame", 1}, {"metric", "bottleneck"}},
                 &data_out, &message),
      -32005);
  EXPECT_EQ(data_out["run"], "legacy-v1");
  EXPECT_EQ(data_out["frame"], 0);
  EXPECT_NE(message.find("run legacy-v1 frame 0"), std::string::npos) << message;
  EXPECT_NE(message.find("fnet-store-1"), std::string::npos) << message;
}

TEST(BlocksService, FnetctlBlocksPrintsTheCellsAsTableCsvAndJson) {
  testing::TempDir tmp;
  const PlantedRun run = plant(testing::lammps_frame(10));
  const fs::path csv = write_run(tmp.path() / "csv", run);
  ServerProcess server = start_server(tmp.path() / "data", 84, tmp.path() / "server.log");
  auto pub = publish(csv, "planted", 84, tmp.path() / "publish.log");
  ASSERT_EQ(pub->wait(120s), 0) << "see " << tmp.path() / "publish.log";
  wait_for_frames(server.port, "planted", 3);
  const fs::path log = tmp.path() / "fnetctl.log";
  const std::vector<std::string> ask{"blocks", "--run",    "planted",      "--frame", "0", "--other-frame",
                                     "1",      "--metric", "wasserstein2", "--k",     "2"};
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = ask;
    a.insert(a.end(), extra.begin(), extra.end());
    return run_fnetctl(server.port, a, log);
  };
  const Outcome as_json = with({"--format", "json"});
  ASSERT_EQ(as_json.code, 0) << as_json.out;
  const json answer = json::parse(as_json.out);
  EXPECT_EQ(answer["largest"]["row"], 1);
  EXPECT_EQ(answer["largest"]["col"], 0);
  // CSV: one row per cell, the values exactly the API's.
  const Outcome as_csv = with({"--format", "csv"});
  ASSERT_EQ(as_csv.code, 0);
  std::istringstream lines(as_csv.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line.rfind("# fnet-server ", 0), 0u) << "the provenance comment first: " << line;
  std::getline(lines, line);
  EXPECT_EQ(line.rfind("row,col,x_lo,", 0), 0u) << line;
  std::size_t rows = 0;
  while (std::getline(lines, line)) {
    const json& cell = answer["cells"][rows++];
    EXPECT_EQ(std::stod(line.substr(line.rfind(',') + 1)), cell["value"].get<double>()) << line;
    EXPECT_EQ(
        line.rfind(std::to_string(cell["row"].get<int>()) + "," + std::to_string(cell["col"].get<int>()) + ",", 0), 0u)
        << line;
  }
  EXPECT_EQ(rows, 4u);
  // The table marks the largest cell.
  const Outcome table = with({});
  ASSERT_EQ(table.code, 0);
  std::size_t marked = 0;
  for (std::istringstream t(table.out); std::getline(t, line);)
    if (line.size() > 2 && line.substr(line.size() - 2) == " *") {
      ++marked;
      EXPECT_EQ(line.substr(0, 9), "   1    0") << line;
    }
  EXPECT_EQ(marked, 1u) << table.out;
  // Usage errors exit 2 before asking the server; an unknown frame is exit 4.
  for (const char* k : {"0", "17"}) {
    const Outcome bad = run_fnetctl(
        server.port, {"blocks", "--frame", "0", "--other-frame", "1", "--metric", "bottleneck", "--k", k}, log);
    EXPECT_EQ(bad.code, 2) << k;
  }
  EXPECT_NE(read_file(log).find("--k must be an integer from 1 to 16, got 17"), std::string::npos) << read_file(log);
  EXPECT_EQ(with({"--format", "xml"}).code, 2);
  EXPECT_EQ(
      run_fnetctl(server.port,
                  {"blocks", "--run", "planted", "--frame", "0", "--other-frame", "7", "--metric", "bottleneck"}, log)
          .code,
      4);
}

// distance.get with explain: k reads both networks back from the store and names the grains of
// the largest terms; for d_B the first term is the one that attains it, and its feature in the
// planted frame lies in the planted corner.
TEST(ExplainService, TheTermsAreTheLibrarysAndTheBottleneckTermLiesInThePlantedCorner) {
  testing::TempDir tmp;
  const PlantedRun run = plant(testing::lammps_frame(10));
  const fs::path csv = write_run(tmp.path() / "csv", run);
  const fs::path data = tmp.path() / "data";
  fs::create_directories(data);
  fs::copy_file(fs::path(FNET_TEST_DATA) / "store-v1" / "legacy-v1.h5", data / "legacy-v1.h5");
  ServerProcess server = start_server(data, 86, tmp.path() / "server.log");
  auto pub = publish(csv, "planted", 86, tmp.path() / "publish.log");
  ASSERT_EQ(pub->wait(120s), 0) << "see " << tmp.path() / "publish.log";
  wait_for_frames(server.port, "planted", 3);
  RpcClient rpc("127.0.0.1", server.port);
  const BlockDomain d = block_domain(run.planted);
  const double mid_x = (d.x_lo + d.x_hi) / 2, mid_y = (d.y_lo + d.y_hi) / 2;
  const auto ask = [&](std::uint32_t a, std::uint32_t b, const std::string& metric, int dim, std::uint32_t k) {
    return rpc.call(
        "distance.get",
        {{"run", "planted"}, {"frame", a}, {"other_frame", b}, {"metric", metric}, {"dim", dim}, {"explain", k}});
  };
  for (const std::string metric : {"bottleneck", "wasserstein2"})
    for (const int dim : {0, 1}) {
      SCOPED_TRACE(metric + " dim " + std::to_string(dim));
      const DistanceMetric m = metric == "bottleneck" ? DistanceMetric::bottleneck() : DistanceMetric::wasserstein(2);
      const json answer = ask(0, 1, metric, dim, 3);
      const Explanation expected =
          explain(run.original, run.planted, {m, dim, ForceKind::normal, EssentialConvention::floor, 3});
      EXPECT_EQ(answer["explain"], explain_terms_json(expected.terms));
      EXPECT_EQ(answer["value"].get<double>(), expected.distance.value);
      ASSERT_FALSE(answer["explain"].empty());
      if (metric == "bottleneck") {
        const json& first = answer["explain"][0];
        EXPECT_EQ(first["cost"].get<double>(), answer["value"].get<double>());
        ASSERT_FALSE(first["b"].is_null()) << first.dump();
        for (const json& xy : first["b"]["birth_simplex"]["positions"]) {
          EXPECT_LT(xy[0].get<double>(), mid_x) << first.dump();
          EXPECT_GT(xy[1].get<double>(), mid_y) << first.dump();
        }
      }
      // An unchanged frame: distance 0, no term of positive cost.
      const json same = ask(0, 2, metric, dim, 3);
      EXPECT_EQ(same["value"].get<double>(), 0.0);
      EXPECT_TRUE(same["explain"].empty()) << same.dump();
    }
  // Without explain the answer has none; bad values are named before any work.
  EXPECT_FALSE(
      rpc.call("distance.get", {{"run", "planted"}, {"frame", 0}, {"other_frame", 1}, {"metric", "bottleneck"}})
          .contains("explain"));
  for (const json& bad : {json(0), json(1001), json("3"), json(-1)}) {
    json data_out;
    EXPECT_EQ(
        error_code(rpc, "distance.get",
                   {{"run", "planted"}, {"frame", 0}, {"other_frame", 1}, {"metric", "bottleneck"}, {"explain", bad}},
                   &data_out),
        -32602)
        << bad;
    EXPECT_EQ(data_out["parameter"], "explain") << bad;
  }
  // A store written before networks were kept cannot be explained, and says why.
  json data_out;
  EXPECT_EQ(
      error_code(rpc, "distance.get",
                 {{"run", "legacy-v1"}, {"frame", 0}, {"other_frame", 1}, {"metric", "bottleneck"}, {"explain", 1}},
                 &data_out),
      -32005);
  EXPECT_EQ(data_out["run"], "legacy-v1");

  // fnetctl explain: the API's answer as JSON, and a table with one row per term.
  const fs::path log = tmp.path() / "fnetctl.log";
  const std::vector<std::string> args{"explain", "--run",    "planted",    "--frame", "0", "--other-frame",
                                      "1",       "--metric", "bottleneck", "--dim",   "1", "--k",
                                      "2"};
  std::vector<std::string> as_json = args;
  as_json.insert(as_json.end(), {"--format", "json"});
  const Outcome j = run_fnetctl(server.port, as_json, log);
  ASSERT_EQ(j.code, 0) << read_file(log);
  EXPECT_EQ(without_time(json::parse(j.out)), without_time(ask(0, 1, "bottleneck", 1, 2)));
  const Outcome table = run_fnetctl(server.port, args, log);
  ASSERT_EQ(table.code, 0) << read_file(log);
  std::size_t rows = 0;
  bool header = false;
  std::string line;
  for (std::istringstream t(table.out); std::getline(t, line);) {
    header |= line.find("rank") != std::string::npos && line.find("where (x, y)") != std::string::npos;
    rows += line.rfind("   1 ", 0) == 0 || line.rfind("   2 ", 0) == 0;
  }
  EXPECT_TRUE(header) << table.out;
  EXPECT_EQ(rows, std::min<std::size_t>(2, ask(0, 1, "bottleneck", 1, 2)["explain"].size())) << table.out;
  EXPECT_EQ(run_fnetctl(server.port,
                        {"explain", "--frame", "0", "--other-frame", "1", "--metric", "bottleneck", "--k", "0"}, log)
                .code,
            2);
  EXPECT_EQ(
      run_fnetctl(server.port,
                  {"explain", "--run", "planted", "--frame", "0", "--other-frame", "9", "--metric", "bottleneck"}, log)
          .code,
      4);
}

}  // namespace
}  // namespace fnet::e2e
