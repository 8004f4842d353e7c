// Approximate mode: the bounds bracket the exact distance and the value is within delta.
#include <gtest/gtest.h>

#include "distance_support.hpp"
#include "distance_test_util.hpp"

namespace fnet::test {
namespace {

void check_bracket(const Diagram& a, const Diagram& b, double q, double delta, const char* what, int trial) {
  const double exact = distance(a, b, q, EssentialConvention::floor).value;
  const DistanceResult r = distance(a, b, q, EssentialConvention::floor, delta);
  const double slack = 1e-12 * std::max(1.0, exact);
  ASSERT_LE(r.lower, exact + slack) << what << " q=" << q << " delta=" << delta << " trial " << trial;
  ASSERT_GE(r.upper, exact - slack) << what << " q=" << q << " delta=" << delta << " trial " << trial;
  ASSERT_EQ(r.value, r.upper);
  ASSERT_LE(r.value - exact, delta * exact + slack) << what << " q=" << q << " delta=" << delta;
  ASSERT_LE(r.upper - r.lower, delta * r.lower + slack) << what;
}

TEST(DistanceApproximation, ThousandsOfRandomPairs) {
  std::mt19937_64 rng(99);
  std::uniform_int_distribution<std::size_t> size(1, 60);
  int pairs = 0;
  for (int trial = 0; trial < 1200; ++trial) {
    const Diagram a = random_diagram(rng, size(rng), 3, trial % 4 == 0);
    const Diagram b = trial % 2 ? perturbed(rng, a, 0.1) : random_diagram(rng, size(rng), 3, false);
    const double delta = trial % 3 == 0 ? 0.1 : trial % 3 == 1 ? 0.01 : 0.001;
    for (const double q : {0.0, 1.0, 2.0}) check_bracket(a, b, q, delta, "random", trial);
    ++pairs;
  }
  EXPECT_EQ(pairs, 1200);
}

TEST(DistanceApproximation, RealisticPairs) {
  const FrameDiagramsPair f8 = lammps_diagrams(8, false), f9 = lammps_diagrams(9, false);
  const FrameDiagramsPair t8 = lammps_diagrams(8, true), t9 = lammps_diagrams(9, true);
  std::mt19937_64 rng(5);
  int trial = 0;
  for (const auto& [a, b] : {std::pair{f8.pd0, f9.pd0}, std::pair{t8.pd0, t9.pd0}}) {
    for (const double delta : {0.1, 0.01, 0.001})
      for (const double q : {0.0, 1.0, 2.0}) check_bracket(a, b, q, delta, "lammps", trial++);
  }
  // Perturbed copies of realistic diagrams: the consecutive-frame regime.
  for (int k = 0; k < 20; ++k) {
    const Diagram& base = k % 2 ? f9.pd0 : t9.pd0;
    const Diagram b = perturbed(rng, base, 0.02 * (k + 1));
    for (const double q : {0.0, 1.0, 2.0}) check_bracket(base, b, q, 0.01, "perturbed", k);
  }
}

}  // namespace
}  // namespace fnet::test
