// The paper's Fig. 2: PD0 = {(128, -1), (119, 74), (113, 83), (106, 76)}. Four components are born
// at 128, 119, 113 and 106; at 83 the 113-component meets the 119-component and dies (the elder
// survives); at 76 the 106-component dies; at 74 the 119-component meets the 128-component and dies.
#include <random>

#include <gtest/gtest.h>

#include "tests/reference/reference_persistence.hpp"
#include "tests/support/diagram_checks.hpp"
#include "tests/support/frame_transforms.hpp"
#include "tests/support/small_frames.hpp"

namespace fnet::testing {
namespace {

// Each component is one strong contact (a vertex takes the value of its strongest edge). Four
// pendant contacts of force 1, 1, 1, 2 on the 128-particle add only zero-length points and bring
// the mean force to exactly 64 = (699 + 5) / 11, so normalized values are the raw ones / 64 exactly.
Frame figure2_frame() {
  return frame_of(12,
                  {
                      both(0, 1, 128),
                      both(2, 3, 119),
                      both(4, 5, 113),
                      both(6, 7, 106),  // the four peaks
                      both(5, 3, 83),   // 113-component meets the 119-component
                      both(7, 2, 76),   // 106-component meets the 119-component
                      both(2, 0, 74),   // 119-component meets the 128-component
                      both(0, 8, 1),
                      both(0, 9, 1),
                      both(0, 10, 1),
                      both(0, 11, 2),
                  },
                  "figure 2");
}

Diagram figure2_pd0_over(double mean) {
  return {{128 / mean, kNeverDies}, {119 / mean, 74 / mean}, {113 / mean, 83 / mean}, {106 / mean, 76 / mean}};
}

TEST(ElderRule, Figure2DiagramInUnitsOfTheMeanForce) {
  const Frame frame = figure2_frame();
  for (ForceKind kind : {ForceKind::normal, ForceKind::tangential}) {
    const ForceNetwork network = build_network(frame, kind);
    ASSERT_EQ(network.mean_force, 64.0);
    const FrameDiagrams d = compute_persistence(network);
    EXPECT_EQ(d.pd0, figure2_pd0_over(64.0));
    EXPECT_TRUE(d.pd1.empty());
    EXPECT_EQ(reference::persistence(frame, kind).pd0, figure2_pd0_over(64.0)) << "the reference itself";
  }
}

// A wrong rule that picks the survivor by label, by the orientation of the contact or by row
// order gives a different diagram for some of these rewritings (e.g. the younger-survives rule
// gives (119, 83), (113, 76), (128, 74), (106, -1)); the elder rule gives the same for all.
TEST(ElderRule, SurvivorDoesNotDependOnLabelsOrientationOrRowOrder) {
  std::mt19937_64 rng(301);
  for (int k = 0; k < 300; ++k) {
    Frame frame = shuffled_rows(relabelled(figure2_frame(), rng), rng);
    if (k % 2) frame = reversed_pairs(frame);
    for (ForceKind kind : {ForceKind::normal, ForceKind::tangential})
      ASSERT_EQ(fast_path(frame, kind).pd0, figure2_pd0_over(64.0)) << describe(frame);
  }
}

// Each peak is born, the merges happen in the paper's order, and the ratios survive any scale:
// births and deaths relative to the 128-peak are the figure's numbers whatever the mean.
TEST(ElderRule, Figure2RatiosWithoutThePendants) {
  const Frame frame = frame_of(8, {both(0, 1, 128), both(2, 3, 119), both(4, 5, 113), both(6, 7, 106), both(5, 3, 83),
                                   both(7, 2, 76), both(2, 0, 74)});
  const Diagram pd0 = fast_path(frame, ForceKind::normal).pd0;
  ASSERT_EQ(pd0.size(), 4u);
  const double unit = pd0[0].birth / 128;  // 1 / mean
  const double expected[4][2] = {{128, -1}, {119, 74}, {113, 83}, {106, 76}};
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR(pd0[k].birth / unit, expected[k][0], 1e-12);
    if (expected[k][1] == -1)
      EXPECT_EQ(pd0[k].death, kNeverDies);
    else
      EXPECT_NEAR(pd0[k].death / unit, expected[k][1], 1e-12);
  }
}

}  // namespace
}  // namespace fnet::testing
