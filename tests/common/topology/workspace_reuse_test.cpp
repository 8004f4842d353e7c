// The fast path keeps buffers per thread between calls, and drops them after a large frame: no
// state may leak from one frame into the next.
#include <random>

#include <gtest/gtest.h>

#include "tests/support/contact_graphs.hpp"
#include "tests/support/diagram_checks.hpp"
#include "tests/support/frame_transforms.hpp"
#include "tests/support/random_forces.hpp"

namespace fnet::testing {
namespace {

Frame small_frame(std::mt19937_64& rng) {
  return frame_from_graph(random_dense(std::uniform_int_distribution<std::size_t>(3, 9)(rng), 0.6, rng),
                          random_style(rng), 1, rng);
}

TEST(WorkspaceReuse, SmallLargeSmallAllMatchTheReference) {
  std::mt19937_64 rng(501);
  for (int round = 0; round < 6; ++round) {
    const Frame large = frame_from_graph(triangular_lattice(40, 40, 0.9, rng), random_style(rng), 50, rng);
    ASSERT_TRUE(matches_reference(small_frame(rng), ForceKind::normal));
    ASSERT_TRUE(matches_reference(large, ForceKind::normal));
    ASSERT_TRUE(matches_reference(small_frame(rng), ForceKind::tangential));
  }
}

TEST(WorkspaceReuse, SameNetworkTwiceGivesTheSameDiagrams) {
  std::mt19937_64 rng(502);
  for (int k = 0; k < 200; ++k) {
    const ForceNetwork net = build_network(small_frame(rng), ForceKind::normal);
    const FrameDiagrams a = compute_persistence(net);
    const FrameDiagrams b = compute_persistence(net);
    ASSERT_EQ(a.pd0, b.pd0);
    ASSERT_EQ(a.pd1, b.pd1);
    ASSERT_EQ(a.triangles, b.triangles);
  }
}

// 300 000 particles (far more than any buffer kept between calls), a few hundred contacts:
// the frame after it must still be right, and so must the huge one.
TEST(WorkspaceReuse, AHugeFrameThenSmallOnes) {
  std::mt19937_64 rng(503);
  Frame huge = frame_from_graph(apollonian(150, rng), ForceStyle{3, 0, 0, 0}, 300000, rng);
  huge = relabelled(huge, rng);  // spread the contacts over the whole index range
  ASSERT_TRUE(matches_reference(huge, ForceKind::normal));
  for (int k = 0; k < 50; ++k)
    ASSERT_TRUE(matches_reference(small_frame(rng), ForceKind::normal)) << "after the huge frame";
}

}  // namespace
}  // namespace fnet::testing
