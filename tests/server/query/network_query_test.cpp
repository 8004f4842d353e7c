// network_query (network.get): a frame's grains and contacts as held, the mean force of each kind
// over the contacts where it is > 0, and the grains' bounding box, against sums done here; in 2D
// and in 3D; an unknown frame named.
#include "server/query/network_query.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "server/query/loaded_frames.hpp"
#include "server/query/query_errors.hpp"
#include "tests/support/fcc_packing.hpp"

namespace fnet::query {
namespace {

// |f| averaged over the contacts where it is > 0.
double mean_positive(const Frame& f, bool normal) {
  double sum = 0;
  int n = 0;
  for (const Contact& c : f.contacts) {
    const double v = std::abs(normal ? c.fn : c.ft);
    if (v > 0) {
      sum += v;
      ++n;
    }
  }
  return n ? sum / n : 0;
}

Frame square() {
  Frame f;
  f.label = "square";
  f.particle_count = 4;
  f.particles = {{0, 0, 0.5}, {1, 0, 0.6}, {1, 1, 0.5}, {0, 1, 0.4}};
  f.contacts = {{0, 1, -2.0, 0.0}, {1, 2, 1.0, 0.3}, {2, 3, 0.0, 0.6}, {3, 0, 3.0, 0.0}};
  return f;
}

TEST(NetworkQuery, GivesTheFrameItsMeanForcesAndItsBoundingBox) {
  LoadedFrames frames;
  frames.add("r", 4, square());
  const NetworkAnswer a = network_query(frames, {"r", 4});
  EXPECT_EQ(a.header.index, 4u);
  EXPECT_EQ(a.network.contacts.size(), 4u);
  EXPECT_EQ(a.network.contacts[0].fn, -2.0) << "forces as received, signed";
  EXPECT_DOUBLE_EQ(a.mean_normal, (2.0 + 1.0 + 3.0) / 3);
  EXPECT_DOUBLE_EQ(a.mean_tangential, (0.3 + 0.6) / 2);
  ASSERT_TRUE(a.domain);
  EXPECT_EQ(a.domain->x_lo, -0.5);
  EXPECT_EQ(a.domain->x_hi, 1.6);
  EXPECT_EQ(a.domain->y_lo, -0.6);
  EXPECT_EQ(a.domain->y_hi, 1.5);
}

TEST(NetworkQuery, A3dFrameKeepsItsZAndItsBoxInZ) {
  const Frame fcc = testing::fcc_frame({.cells = 2});
  LoadedFrames frames;
  frames.add("fcc", 0, fcc);
  const NetworkAnswer a = network_query(frames, {"fcc", 0});
  EXPECT_EQ(a.network.dimension, 3);
  ASSERT_EQ(a.network.particles.size(), fcc.particles.size());
  double z_lo = std::numeric_limits<double>::infinity(), z_hi = -z_lo;
  for (std::size_t g = 0; g < fcc.particles.size(); ++g) {
    EXPECT_EQ(a.network.particles[g].z, fcc.particles[g].z);
    z_lo = std::min(z_lo, fcc.particles[g].z - fcc.particles[g].r);
    z_hi = std::max(z_hi, fcc.particles[g].z + fcc.particles[g].r);
  }
  ASSERT_TRUE(a.domain);
  EXPECT_EQ(a.domain->z_lo, z_lo);
  EXPECT_EQ(a.domain->z_hi, z_hi);
  EXPECT_DOUBLE_EQ(a.mean_normal, mean_positive(fcc, true));
  EXPECT_DOUBLE_EQ(a.mean_tangential, mean_positive(fcc, false));
}

TEST(NetworkQuery, AFrameNotHeldIsNamed) {
  LoadedFrames frames;
  frames.add("r", 0, square());
  try {
    network_query(frames, {"r", 7});
    ADD_FAILURE() << "frame 7 was found";
  } catch (const UnknownFrame& e) {
    EXPECT_EQ(e.run, "r");
    EXPECT_EQ(e.frame, 7u);
  }
}

}  // namespace
}  // namespace fnet::query
