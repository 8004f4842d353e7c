// Diagrams describe the packing, not how its file was written: row order, pair orientation and
// particle labels must not change them at all; a common force scale must not change them beyond
// rounding (normalization divides it out).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "tests/support/contact_graphs.hpp"
#include "tests/support/diagram_checks.hpp"
#include "tests/support/frame_transforms.hpp"
#include "tests/support/random_forces.hpp"

namespace fnet::testing {
namespace {

constexpr ForceKind kInvariantKinds[] = {ForceKind::normal, ForceKind::tangential};

// A frame from one of the graph families, with a random force style (ties, zeros, negatives and,
// if allowed, near-ties a few ulps apart).
Frame random_frame(std::mt19937_64& rng, bool near_ties = true) {
  const auto pick = [&](std::size_t lo, std::size_t hi) {
    return std::uniform_int_distribution<std::size_t>(lo, hi)(rng);
  };
  Graph g;
  switch (pick(0, 4)) {
    case 0:
      g = triangular_lattice(pick(2, 6), pick(2, 6), 0.8, rng);
      break;
    case 1:
      g = square_lattice(pick(2, 6), pick(2, 6), 0.9, 0.3, rng);
      break;
    case 2:
      g = apollonian(pick(1, 25), rng);
      break;
    case 3:
      g = random_dense(pick(4, 10), 0.6, rng);
      break;
    default:
      g = bipartite_k33_with_chords(pick(0, 6), rng);
      break;
  }
  ForceStyle style = random_style(rng);
  if (!near_ties) style.ulp_jitter = 0;
  return frame_from_graph(g, style, pick(0, 2), rng);
}

// Applies `change` to many frames and expects identical diagrams for both force kinds.
template <class Change>
void expect_identical_after(std::uint64_t seed, Change change) {
  std::mt19937_64 rng(seed);
  for (int k = 0; k < 1500; ++k) {
    const Frame frame = random_frame(rng);
    const Frame changed = change(frame, rng);
    for (ForceKind kind : kInvariantKinds) {
      const FrameDiagrams a = fast_path(frame, kind), b = fast_path(changed, kind);
      ASSERT_EQ(a.pd0, b.pd0) << to_string(kind) << ", case " << k << "\n"
                              << describe(frame) << "changed:\n"
                              << describe(changed);
      ASSERT_EQ(a.pd1, b.pd1) << to_string(kind) << ", case " << k << "\n"
                              << describe(frame) << "changed:\n"
                              << describe(changed);
      ASSERT_EQ(a.triangles, b.triangles);
    }
  }
}

TEST(PersistenceInvariance, PermutingRowsGivesIdenticalDiagrams) {
  expect_identical_after(201, [](const Frame& f, std::mt19937_64& rng) { return shuffled_rows(f, rng); });
}

TEST(PersistenceInvariance, ReversingPairsGivesIdenticalDiagrams) {
  expect_identical_after(202, [](const Frame& f, std::mt19937_64&) { return reversed_pairs(f); });
}

TEST(PersistenceInvariance, PermutingParticleLabelsGivesIdenticalDiagrams) {
  expect_identical_after(203, [](const Frame& f, std::mt19937_64& rng) { return relabelled(f, rng); });
}

TEST(PersistenceInvariance, AllThreeTogetherGiveIdenticalDiagrams) {
  expect_identical_after(
      204, [](const Frame& f, std::mt19937_64& rng) { return shuffled_rows(reversed_pairs(relabelled(f, rng)), rng); });
}

// Multiplying by a power of two is exact in binary floating point, so the normalized values, and
// the diagrams, must be bit-identical.
TEST(PersistenceInvariance, ScalingByAPowerOfTwoIsExact) {
  for (double factor : {std::ldexp(1.0, -40), std::ldexp(1.0, 30)})
    expect_identical_after(205, [factor](const Frame& f, std::mt19937_64&) { return scaled(f, factor); });
}

// Frames past 256 edges, where build_network switches to its radix sort.
TEST(PersistenceInvariance, LargeFramesUnderAllRewritings) {
  std::mt19937_64 rng(207);
  for (int k = 0; k < 30; ++k) {
    const Frame frame = frame_from_graph(triangular_lattice(15, 15, 0.9, rng), random_style(rng), 3, rng);
    const Frame changed = shuffled_rows(reversed_pairs(relabelled(frame, rng)), rng);
    for (ForceKind kind : kInvariantKinds) {
      const FrameDiagrams a = fast_path(frame, kind), b = fast_path(changed, kind);
      ASSERT_EQ(a.pd0, b.pd0) << to_string(kind) << ", case " << k;
      ASSERT_EQ(a.pd1, b.pd1) << to_string(kind) << ", case " << k;
    }
  }
}

// Values a few ulps apart are left out here: rounding the scaled values may make them equal (a
// point of length 1 ulp then drops out as zero-length), which is rounding, not a dependence on scale.
TEST(PersistenceInvariance, ScalingAllForcesChangesNothingBeyondRounding) {
  for (double factor : {1e-12, 1e6, 3.7}) {
    std::mt19937_64 rng(206);
    for (int k = 0; k < 1500; ++k) {
      const Frame frame = random_frame(rng, false);
      for (ForceKind kind : kInvariantKinds) {
        const FrameDiagrams a = fast_path(frame, kind), b = fast_path(scaled(frame, factor), kind);
        ASSERT_TRUE(nearly_equal(a.pd0, b.pd0, 1e-12)) << "factor " << factor << ", " << to_string(kind) << "\n"
                                                       << describe(frame);
        ASSERT_TRUE(nearly_equal(a.pd1, b.pd1, 1e-12)) << "factor " << factor << ", " << to_string(kind) << "\n"
                                                       << describe(frame);
      }
    }
  }
}

}  // namespace
}  // namespace fnet::testing
