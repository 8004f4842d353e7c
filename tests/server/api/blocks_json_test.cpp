// blocks.get's answer as JSON: a 3D grid's cells carry their layer and z bounds; a 2D one is
// written as it always was, without them.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "server/api/block_methods.hpp"
#include "server/query/loaded_frames.hpp"
#include "tests/support/fcc_packing.hpp"
#include "tests/support/lammps_frames.hpp"

namespace fnet::server {
namespace {

using nlohmann::json;

json answer_for(const Frame& a, const Frame& b, int k) {
  query::LoadedFrames frames;
  frames.add("r", 0, a);
  frames.add("r", 1, b);
  query::BlockRequest r;
  r.run = "r";
  r.frame = 0;
  r.other_frame = 1;
  r.k = k;
  r.measure = {parse_metric("bottleneck"), 0, ForceKind::normal, EssentialConvention::floor};
  return blocks_json(r, query::block_query(frames, r));
}

std::set<std::string> keys(const json& object) {
  std::set<std::string> out;
  for (auto it = object.begin(); it != object.end(); ++it) out.insert(it.key());
  return out;
}

TEST(BlocksJson, A3DGridsCellsCarryTheirLayerAndZBoundsLayerByLayer) {
  const Frame a = testing::fcc_frame({.cells = 3, .seed = 1}), b = testing::fcc_frame({.cells = 3, .seed = 2});
  const json got = answer_for(a, b, 3);
  EXPECT_EQ(got["dimension"], 3);
  ASSERT_EQ(got["cells"].size(), 27u);
  for (int n = 0; n < 27; ++n) {
    const json& cell = got["cells"][n];
    EXPECT_EQ(keys(cell),
              (std::set<std::string>{"layer", "row", "col", "bounds", "contacts", "points", "value", "infinite"}));
    EXPECT_EQ(cell["layer"], n / 9);
    EXPECT_EQ(cell["row"], n / 3 % 3);
    EXPECT_EQ(cell["col"], n % 3);
    ASSERT_EQ(cell["bounds"].size(), 2u);
    EXPECT_EQ(cell["bounds"][0].size(), 6u);
    EXPECT_EQ(cell["bounds"][1].size(), 6u);
    EXPECT_LT(cell["bounds"][0][4].get<double>(), cell["bounds"][0][5].get<double>());
  }
  // Layer 0 starts at the lowest z of a sphere's surface.
  double z_lo = 1e300;
  for (const Particle& p : a.particles) z_lo = std::min(z_lo, p.z - p.r);
  EXPECT_EQ(got["cells"][0]["bounds"][0][4], z_lo);
  EXPECT_EQ(keys(got["largest"]), (std::set<std::string>{"layer", "row", "col", "value"}));
}

TEST(BlocksJson, A2DGridIsWrittenWithoutLayers) {
  const json got = answer_for(testing::lammps_frame(9), testing::lammps_frame(10), 2);
  EXPECT_EQ(got["dimension"], 2);
  ASSERT_EQ(got["cells"].size(), 4u);
  for (const json& cell : got["cells"]) {
    EXPECT_EQ(keys(cell), (std::set<std::string>{"row", "col", "bounds", "contacts", "points", "value", "infinite"}));
    EXPECT_EQ(cell["bounds"][0].size(), 4u);
  }
  EXPECT_EQ(keys(got["largest"]), (std::set<std::string>{"row", "col", "value"}));
}

}  // namespace
}  // namespace fnet::server
