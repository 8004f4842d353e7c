// build_network: which contacts are edges, the mean they are normalized by, and the order it promises.
#include "common/topology/force_network.hpp"

#include <random>
#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/contact_graphs.hpp"
#include "tests/support/frame_transforms.hpp"
#include "tests/support/random_forces.hpp"
#include "tests/support/small_frames.hpp"

namespace fnet::testing {
namespace {

TEST(ForceNetwork, MeanIsOverContactsWithNonZeroForceOnly) {
  // |fn| = 4, 2, 0, 6 -> mean 4 over three contacts; ft = 1, 0, 0, 3 -> mean 2 over two.
  const Frame frame = frame_of(5, {{0, 1, 4, 1}, {1, 2, -2, 0}, {2, 3, 0, 0}, {3, 4, 6, 3}});
  const ForceNetwork normal = build_network(frame, ForceKind::normal);
  EXPECT_EQ(normal.mean_force, 4.0);
  EXPECT_EQ(normal.vertex_count, 5u);
  ASSERT_EQ(normal.edges.size(), 3u);
  EXPECT_EQ(normal.edges[0].value, 1.5);  // 6 / 4, strongest first
  EXPECT_EQ(normal.edges[1].value, 1.0);
  EXPECT_EQ(normal.edges[2].value, 0.5);  // the tensile contact enters with |fn|
  const ForceNetwork tangential = build_network(frame, ForceKind::tangential);
  EXPECT_EQ(tangential.mean_force, 2.0);
  ASSERT_EQ(tangential.edges.size(), 2u);
  EXPECT_EQ(tangential.edges[0].value, 1.5);
  EXPECT_EQ(tangential.edges[1].value, 0.5);
}

TEST(ForceNetwork, EdgesHaveTheSmallerIndexFirst) {
  const ForceNetwork net = build_network(frame_of(4, {both(3, 1, 1), both(2, 0, 2)}), ForceKind::normal);
  ASSERT_EQ(net.edges.size(), 2u);
  EXPECT_EQ(net.edges[0].u, 0u);
  EXPECT_EQ(net.edges[0].v, 2u);
  EXPECT_EQ(net.edges[1].u, 1u);
  EXPECT_EQ(net.edges[1].v, 3u);
}

TEST(ForceNetwork, NoForceMeansNoEdgesAndZeroMean) {
  const ForceNetwork net = build_network(frame_of(3, {both(0, 1, 0.0), {1, 2, -0.0, 0.0}}), ForceKind::normal);
  EXPECT_TRUE(net.edges.empty());
  EXPECT_EQ(net.mean_force, 0.0);
  EXPECT_EQ(net.vertex_count, 3u);
}

// force_network.hpp: edges are kept "value descending (ties in an order that does not depend on
// the order of the input rows)". Two frames that differ only in row order must give the same edges.
TEST(ForceNetwork, TieOrderDoesNotDependOnRowOrder) {
  const auto same_edges = [](const ForceNetwork& a, const ForceNetwork& b) {
    if (a.edges.size() != b.edges.size()) return false;
    for (std::size_t k = 0; k < a.edges.size(); ++k)
      if (a.edges[k].u != b.edges[k].u || a.edges[k].v != b.edges[k].v || a.edges[k].value != b.edges[k].value)
        return false;
    return true;
  };
  // The smallest case: two contacts with equal force, listed in both orders.
  const ForceNetwork ab = build_network(frame_of(4, {both(0, 1, 1.0), both(2, 3, 1.0)}), ForceKind::normal);
  const ForceNetwork ba = build_network(frame_of(4, {both(2, 3, 1.0), both(0, 1, 1.0)}), ForceKind::normal);
  EXPECT_TRUE(same_edges(ab, ba)) << "first edge (" << ab.edges[0].u << "," << ab.edges[0].v << ") vs ("
                                  << ba.edges[0].u << "," << ba.edges[0].v << ")";
  // And on frames large enough for the radix sort (>= 256 edges).
  std::mt19937_64 rng(401);
  const Frame big = frame_from_graph(triangular_lattice(12, 12, 1.0, rng), ForceStyle{3, 0, 0, 0}, 0, rng);
  EXPECT_TRUE(
      same_edges(build_network(big, ForceKind::normal), build_network(shuffled_rows(big, rng), ForceKind::normal)));
}

TEST(ForceKindNames, ParseAndPrint) {
  EXPECT_EQ(parse_force_kind("normal"), ForceKind::normal);
  EXPECT_EQ(parse_force_kind("tangential"), ForceKind::tangential);
  EXPECT_EQ(to_string(ForceKind::normal), "normal");
  EXPECT_EQ(to_string(ForceKind::tangential), "tangential");
  try {
    parse_force_kind("Normal");
    ADD_FAILURE() << "accepted 'Normal'";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("'Normal'"));
  }
}

}  // namespace
}  // namespace fnet::testing
