// pair_query's explanation between two 3D frames, as distance.get and fnet-analyze explain serve
// it: every grain's position carries its z, in the terms and in their JSON.
#include "server/query/pair_query.hpp"

#include <gtest/gtest.h>

#include "common/codec/explain_json.hpp"
#include "server/query/loaded_frames.hpp"
#include "tests/support/fcc_packing.hpp"

namespace fnet::query {
namespace {

TEST(PairQuery3D, ExplainedGrainsCarryTheirZ) {
  const Frame a = testing::fcc_frame({.cells = 3, .seed = 1}), b = testing::fcc_frame({.cells = 3, .seed = 2});
  LoadedFrames frames;
  frames.add("a", 0, a);
  frames.add("b", 0, b);
  const PairAnswer got =
      pair_query(frames, {"a", 0, "b", 0, {parse_metric("wasserstein2"), 1, ForceKind::normal}, 0, std::size_t{3}});
  ASSERT_TRUE(got.explained);
  ASSERT_EQ(got.explained->size(), 3u);
  const nlohmann::json terms = explain_terms_json(*got.explained);
  std::size_t checked = 0;
  for (std::size_t t = 0; t < 3; ++t)
    for (const char* side : {"a", "b"}) {
      const auto& point = side[0] == 'a' ? (*got.explained)[t].a : (*got.explained)[t].b;
      if (!point) continue;
      const Frame& frame = side[0] == 'a' ? a : b;
      const nlohmann::json& simplex = terms[t][side]["birth_simplex"];
      ASSERT_EQ(simplex["grains"].size(), 2u) << "a PD1 class is born at a contact";
      for (std::size_t g = 0; g < 2; ++g) {
        const Particle& p = frame.particles[point->birth_simplex.grains[g]];
        EXPECT_EQ(point->birth_simplex.positions[g], (std::array<double, 3>{p.x, p.y, p.z}));
        EXPECT_EQ(simplex["positions"][g], nlohmann::json({p.x, p.y, p.z}));
        ++checked;
      }
    }
  EXPECT_GE(checked, 6u);
}

}  // namespace
}  // namespace fnet::query
