// block_query on 3D frames: a change planted in one cell of the k x k x k grid is located there,
// every other cell is unchanged, and frames of two dimensions are refused by name.
#include "server/query/block_query.hpp"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "server/query/loaded_frames.hpp"
#include "server/query/query_errors.hpp"
#include "tests/support/fcc_packing.hpp"
#include "tests/support/grid_cells.hpp"

namespace fnet::query {
namespace {

BlockRequest request(int k) {
  BlockRequest r;
  r.run = "fcc";
  r.frame = 0;
  r.other_frame = 1;
  r.k = k;
  r.measure = {parse_metric("bottleneck"), 0, ForceKind::normal, EssentialConvention::floor};
  return r;
}

TEST(BlockQuery3D, AChangePlantedInOneCellIsLocatedThere) {
  const Frame a = testing::fcc_frame({.cells = 5});
  // Cell (layer 2, row 0, col 1) of a 3 x 3 x 3 grid: three different indices, so that no two axes
  // can be swapped unseen.
  const std::vector<std::size_t> planted = testing::contacts_in_cell(a, 3, 2, 0, 1, 0.2);
  ASSERT_GE(planted.size(), 20u);
  const Frame b = testing::strengthen(a, planted, 20);
  LoadedFrames frames;
  frames.add("fcc", 0, a);
  frames.add("fcc", 1, b);
  for (const std::string metric : {"bottleneck", "wasserstein1"})
    for (const int dim : {0, 1}) {
      BlockRequest r = request(3);
      r.measure.metric = parse_metric(metric);
      r.measure.dim = dim;
      const BlockAnswer got = block_query(frames, r);
      ASSERT_EQ(got.cells.size(), 27u);
      ASSERT_EQ(got.distances.size(), 27u);
      const std::size_t target = (2 * 3 + 0) * 3 + 1;
      EXPECT_EQ(got.largest, target) << metric << " PD" << dim;
      EXPECT_EQ(got.cells[target].layer, 2);
      EXPECT_EQ(got.cells[target].row, 0);
      EXPECT_EQ(got.cells[target].col, 1);
      for (std::size_t c = 0; c < 27; ++c) {
        if (c == target) {
          EXPECT_GT(got.distances[c].distance.value, 0) << metric << " PD" << dim;
        } else {
          EXPECT_EQ(got.distances[c].distance.value, 0) << metric << " PD" << dim << " cell " << c;
        }
      }
    }
}

TEST(BlockQuery3D, FramesOfTwoDimensionsAreRefusedByName) {
  const Frame a = testing::fcc_frame({.cells = 2});
  Frame flat = a;
  flat.dimension = 2;
  for (Particle& p : flat.particles) p.z = 0;
  LoadedFrames frames;
  frames.add("fcc", 0, a);
  frames.add("fcc", 1, flat);
  try {
    block_query(frames, request(2));
    ADD_FAILURE() << "accepted";
  } catch (const NoNetwork& e) {
    EXPECT_EQ(e.frame, 1u);
    EXPECT_NE(std::string(e.what()).find("frame 1 is 2D and frame 0 3D"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fnet::query
