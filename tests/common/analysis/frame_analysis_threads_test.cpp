// The analysis of a frame on two threads gives what it gives on one, bit for bit; the jobs take a
// thread count and an accepted relative error.
#include <cstring>

#include <gtest/gtest.h>

#include "common/analysis/run_pipeline.hpp"
#include "tests/support/synthetic_frame.hpp"

namespace fnet {
namespace {

bool same_bits(const Diagram& a, const Diagram& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(PersistencePoint)) == 0;
}

TEST(FrameAnalysisThreads, TwoThreadsGiveTheSameDiagramsAndDistancesBitForBit) {
  for (const int dimension : {2, 3}) {
    SCOPED_TRACE(dimension);
    const Frame first = testing::synthetic_frame(testing::disordered_packing(dimension, 1500, 4));
    const Frame next = testing::next_frame(first, {.seed = 4});
    const FrameDiagramSet previous = analyze_frame(first), one = analyze_frame(next), two = analyze_frame(next, 2);
    for (const ForceKind force : kForces)
      for (int dim = 0; dim < 2; ++dim)
        EXPECT_TRUE(same_bits(diagram_of(one, force, dim), diagram_of(two, force, dim)));
    const StepDistances serial = step_distances(previous, one),
                        shared = step_distances(previous, one, EssentialConvention::floor, 2);
    for (std::size_t k = 0; k < kStoredSeries.size(); ++k) {
      EXPECT_EQ(std::memcmp(&serial.value[k], &shared.value[k], sizeof(double)), 0) << series_key(kStoredSeries[k]);
      EXPECT_GT(serial.value[k], 0) << series_key(kStoredSeries[k]);
      EXPECT_GE(shared.seconds[k], 0);
    }
  }
}

TEST(FrameAnalysisThreads, TheJobsTakeTheirThreadCount) {
  auto first = std::make_shared<const Frame>(testing::synthetic_frame(testing::disordered_packing(2, 800, 5)));
  auto next = std::make_shared<const Frame>(testing::next_frame(*first, {.seed = 5}));
  const DiagramOutcome a = DiagramJob{0, first, 2}.run(), b = DiagramJob{1, next, 2}.run();
  ASSERT_TRUE(a.diagrams && b.diagrams);
  const auto pa = std::make_shared<const FrameDiagramSet>(*a.diagrams),
             pb = std::make_shared<const FrameDiagramSet>(*b.diagrams);
  const DistanceOutcome two = DistanceJob{1, pa, pb, EssentialConvention::floor, 2}.run();
  const DistanceOutcome one = DistanceJob{1, pa, pb}.run();
  EXPECT_EQ(std::memcmp(two.distances.value.data(), one.distances.value.data(), sizeof(double) * kStoredSeries.size()),
            0);
}

}  // namespace
}  // namespace fnet
