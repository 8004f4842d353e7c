// 3D frames through the service: a run file of a jittered FCC packing (fnet-run-3) published over
// DDS to a real fnet-server, which stores each frame with its z; blocks.get cuts it into
// k x k x k cells and finds a change planted in one of them, distance.get's explanation carries
// each grain's z, and fnetctl blocks prints the cells with their layer.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "client/rpc/rpc_client.hpp"
#include "common/analysis/blocks.hpp"
#include "tests/e2e/planted_fcc_run.hpp"
#include "tests/e2e/process.hpp"
#include "tests/e2e/service_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

namespace fs = std::filesystem;
using client::json;
using namespace std::chrono_literals;

constexpr int kDomain3D = 87;  // CONTRIBUTING.md: the 3D blocks and explain service test

TEST(Service3D, BlocksFindThePlantedCellAndExplainedGrainsCarryTheirZ) {
  testing::TempDir tmp;
  // A change planted in cell (layer 2, row 0, col 1) of a 3 x 3 x 3 grid: three different indices,
  // so that no two axes can be swapped unseen.
  const Planted3D run = plant_in_cell({});
  const fs::path file = write_run_file_3d(tmp.path() / "fcc3d.run.h5", "fcc3d", run);
  ServerProcess server = start_server(tmp.path() / "data", kDomain3D, tmp.path() / "server.log");
  ASSERT_EQ(publish_run_file(file, kDomain3D, tmp.path() / "publish.log"), 0) << "see " << tmp.path() / "publish.log";
  wait_for_frames(server.port, "fcc3d", 3);
  client::RpcClient rpc("127.0.0.1", server.port);

  // The run is listed, and its series served, as 3D: its rho is a volume fraction.
  const json runs = rpc.call("runs.list", json::object());
  ASSERT_EQ(runs["runs"].size(), 1u) << runs.dump();
  EXPECT_EQ(runs["runs"][0]["dimension"], 3) << runs.dump();
  EXPECT_EQ(rpc.call("series.get", {{"run", "fcc3d"}, {"metric", "bottleneck"}})["dimension"], 3);

  for (const int dim : {0, 1}) {
    SCOPED_TRACE("PD" + std::to_string(dim));
    const json got = rpc.call(
        "blocks.get",
        {{"run", "fcc3d"}, {"frame", 0}, {"other_frame", 1}, {"k", 3}, {"metric", "bottleneck"}, {"dim", dim}});
    EXPECT_EQ(got["dimension"], 3);
    ASSERT_EQ(got["cells"].size(), 27u);
    EXPECT_EQ(got["largest"]["layer"], 2) << got["largest"];
    EXPECT_EQ(got["largest"]["row"], 0);
    EXPECT_EQ(got["largest"]["col"], 1);
    // The cells the library cuts from the frames as they were written: the store kept every z.
    const auto cells = split_into_blocks(run.original, 3);
    const auto expected =
        block_distances(cells, split_into_blocks(run.planted, 3), DistanceMetric::bottleneck(), dim, ForceKind::normal);
    for (std::size_t c = 0; c < 27; ++c) {
      const json& cell = got["cells"][c];
      EXPECT_EQ(cell["layer"], cells[c].layer);
      EXPECT_EQ(cell["bounds"][0], json(std::vector<double>(cells[c].bounds.begin(), cells[c].bounds.end())));
      EXPECT_EQ(cell["contacts"][0], cells[c].contacts.size());
      EXPECT_EQ(cell["value"].get<double>(), expected[c].distance.value) << c;
      if (c != (2 * 3 + 0) * 3 + 1) {
        EXPECT_EQ(cell["value"].get<double>(), 0.0) << "an unchanged cell, " << cell.dump();
      }
    }
  }

  // The explanation of the change: every grain's position is (x, y, z) as written.
  const json answer = rpc.call(
      "distance.get",
      {{"run", "fcc3d"}, {"frame", 0}, {"other_frame", 1}, {"metric", "bottleneck"}, {"dim", 1}, {"explain", 2}});
  ASSERT_FALSE(answer["explain"].empty()) << answer.dump();
  std::size_t positions = 0;
  for (const json& term : answer["explain"])
    for (const char* side : {"a", "b"}) {
      if (term[side].is_null()) continue;
      const Frame& frame = side[0] == 'a' ? run.original : run.planted;
      const json& simplex = term[side]["birth_simplex"];
      for (std::size_t g = 0; g < simplex["grains"].size(); ++g) {
        const Particle& p = frame.particles[simplex["grains"][g].get<std::size_t>()];
        EXPECT_EQ(simplex["positions"][g], json({p.x, p.y, p.z}));
        ++positions;
      }
    }
  EXPECT_GT(positions, 0u);

  // fnetctl blocks: the table names the grid and a layer column, the largest starred once.
  const Outcome table = run_fnetctl(server.port,
                                    {"blocks", "--run", "fcc3d", "--frame", "0", "--other-frame", "1", "--k", "3",
                                     "--metric", "bottleneck", "--dim", "0"},
                                    tmp.path() / "fnetctl.log");
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_NE(table.out.find("3 x 3 x 3 blocks"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("layer 0 = lowest z"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find(" layer row  col"), std::string::npos) << table.out;
  const std::string rows = table.out.substr(table.out.find('\n'));  // the header line explains the *
  EXPECT_EQ(std::count(rows.begin(), rows.end(), '*'), 1) << table.out;
  const std::size_t star = rows.find(" *");
  ASSERT_NE(star, std::string::npos) << table.out;
  EXPECT_EQ(rows.substr(rows.rfind('\n', star) + 1, 15), "     2   0    1") << table.out;
}

}  // namespace
}  // namespace fnet::e2e
