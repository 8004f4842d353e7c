// block_query on 3D frames: a change planted in one cell of the k x k x k grid is located there,
// every other cell is unchanged, and frames of two dimensions are refused by name.
#include "server/query/block_query.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "server/query/loaded_frames.hpp"
#include "server/query/query_errors.hpp"
#include "tests/support/fcc_packing.hpp"

namespace fnet::query {
namespace {

// The box of the frame's spheres, worked out here on its own: lo and hi on each axis.
std::array<std::array<double, 2>, 3> box_of(const Frame& f) {
  std::array<std::array<double, 2>, 3> box;
  for (auto& axis : box) axis = {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const Particle& p : f.particles) {
    const double at[3] = {p.x, p.y, p.z};
    for (int axis = 0; axis < 3; ++axis)
      box[axis] = {std::min(box[axis][0], at[axis] - p.r), std::max(box[axis][1], at[axis] + p.r)};
  }
  return box;
}

// The contacts whose contact point lies in cell (layer, row, col) of a k x k x k grid over the
// frame's box, at least `margin` inside its faces.
std::vector<std::size_t> contacts_in_cell(const Frame& f, int k, int layer, int row, int col, double margin) {
  const auto box = box_of(f);
  const int index[3] = {col, row, layer};
  std::vector<std::size_t> out;
  for (std::size_t n = 0; n < f.contacts.size(); ++n) {
    const Particle &a = f.particles[f.contacts[n].i], &b = f.particles[f.contacts[n].j];
    const double d[3] = {b.x - a.x, b.y - a.y, b.z - a.z};
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double point[3] = {a.x + a.r * d[0] / len, a.y + a.r * d[1] / len, a.z + a.r * d[2] / len};
    bool inside = true;
    for (int axis = 0; axis < 3; ++axis) {
      const double width = (box[axis][1] - box[axis][0]) / k;
      const double lo = box[axis][0] + width * index[axis], hi = lo + width;
      inside = inside && point[axis] > lo + margin && point[axis] < hi - margin;
    }
    if (inside) out.push_back(n);
  }
  return out;
}

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
  const std::vector<std::size_t> planted = contacts_in_cell(a, 3, 2, 0, 1, 0.2);
  ASSERT_GE(planted.size(), 20u);
  Frame b = a;
  for (std::size_t k = 0; k < 20; ++k) {
    Contact& c = b.contacts[planted[k]];
    c.fn *= 3 + 0.1 * static_cast<double>(k % 4), c.ft *= 2;
  }
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
