// An optimality certificate checked from the definitions, where no reference solver can run
// (tens of thousands of points) and for exponents the oracles do not cover. For any numbers
// pi(a_i), pi(b_j), pi(HA), pi(HB) LP duality on the assignment form of the matching problem gives
// a lower bound on the optimum:
//   n pi(HB) - m pi(HA) + sum_j pi(b_j) - sum_i pi(a_i) - sum over every arc of max(0, -reduced cost)
// (pair arcs a_i -> b_j of cost c_ij, a_i -> HB of cost da_i, HA -> b_j of cost db_j; reduced cost
// = cost + pi(tail) - pi(head); HA -> HB is uncapacitated, so pi(HA) >= pi(HB) is required). Pairs
// with c_ij >= da_i + db_j are left out of the LP: sending both points to the diagonal instead is
// never dearer, so the optimum stays the same. The
// test computes that bound itself from the solver's potentials, scanning every pair, and checks
// it meets the cost of the solver's matching, recomputed from the matching itself. A suboptimal
// matching leaves a gap, whatever the solver's own bookkeeping says.
#include <chrono>

#include <gtest/gtest.h>

#include "distance_support.hpp"
#include "distance_test_util.hpp"

namespace fnet::test {
namespace {

// The certificate of the solver run on the points as given, and the public distance (which rescales
// them by a power of two first, exactly) must give the same value.
void expect_certified(const Diagram& da, const Diagram& db, double q, const std::string& what) {
  const std::vector<PlanePoint> a = plane(da), b = plane(db);
  ASSERT_FALSE(a.empty() || b.empty()) << what << ": the certificate needs points on both sides";
  const Certificate cert = certify_wasserstein(a, b, q);
  EXPECT_NEAR(std::pow(cert.primal, 1 / q), wasserstein_distance(da, db, {.q = q}).value,
              1e-12 * std::pow(cert.primal, 1 / q))
      << what << " q=" << q;
  EXPECT_TRUE(cert.matching_valid) << what;
  EXPECT_LE(cert.primal - cert.dual, 1e-11 * std::max(1.0, cert.primal))
      << what << " q=" << q << ": matching " << cert.primal << ", dual bound " << cert.dual;
  EXPECT_LE(cert.dual - cert.primal, 1e-11 * std::max(1.0, cert.primal)) << what << " (weak duality broken)";
}

TEST(DistanceDualCertificate, RandomPairsSeveralExponents) {
  std::mt19937_64 rng(404);
  std::uniform_int_distribution<std::size_t> size(1, 300);
  for (int trial = 0; trial < 120; ++trial) {
    const Diagram a = random_diagram(rng, size(rng), 4, trial % 5 == 0);
    const Diagram b = trial % 2 ? perturbed(rng, a, 0.05) : random_diagram(rng, size(rng), 4, trial % 7 == 0);
    for (const double q : {1.0, 1.5, 2.0, 3.0}) expect_certified(a, b, q, "trial " + std::to_string(trial));
  }
}

TEST(DistanceDualCertificate, LammpsFramePairs) {
  for (const bool tangential : {false, true}) {
    const FrameDiagramsPair f8 = lammps_diagrams(8, tangential), f9 = lammps_diagrams(9, tangential);
    for (const double q : {1.0, 2.0}) {
      expect_certified(f8.pd0, f9.pd0, q, "pd0 8->9");
      expect_certified(f8.pd1, f9.pd1, q, "pd1 8->9");
    }
  }
}

// Large q: the solver works in units of the bottleneck distance (wasserstein.cpp); the certificate
// is checked in the same units, with the costs it finds too long for any optimal matching left
// infinite rather than capped.
void expect_certified_in_bottleneck_units(const Diagram& da, const Diagram& db, double q, const std::string& what) {
  const std::vector<PlanePoint> a = plane(da), b = plane(db);
  ASSERT_FALSE(a.empty() || b.empty()) << what;
  const double unit = bottleneck_distance(da, db).value;
  const Certificate cert = certify_wasserstein(a, b, q, unit);
  EXPECT_TRUE(cert.matching_valid) << what;
  EXPECT_GE(cert.primal, 1) << what << " q=" << q << ": a matching without a term >= d_B";
  EXPECT_LE(cert.primal - cert.dual, 1e-11 * cert.primal)
      << what << " q=" << q << ": matching " << cert.primal << ", dual bound " << cert.dual;
  EXPECT_LE(cert.dual - cert.primal, 1e-11 * cert.primal) << what << " (weak duality broken)";
  WassersteinStats st;
  const double value = wasserstein_distance(da, db, {.q = q}, &st).value;
  EXPECT_TRUE(close(unit * std::pow(cert.primal, 1 / q), value, 1e-12)) << what << " q=" << q;
  EXPECT_TRUE(close(st.dual_lower, value, 1e-12)) << what << " q=" << q;
}

TEST(DistanceDualCertificate, LargeExponentsInBottleneckUnits) {
  std::mt19937_64 rng(405);
  std::uniform_int_distribution<std::size_t> size(1, 200);
  for (int trial = 0; trial < 30; ++trial) {
    const Diagram a = random_diagram(rng, size(rng), 4, trial % 5 == 0);
    const Diagram b = trial % 2 ? perturbed(rng, a, 0.05) : random_diagram(rng, size(rng), 4, trial % 7 == 0);
    if (bottleneck_distance(a, b).value == 0) continue;
    for (const double q : {3.0, 10.0, 100.0, 1000.0, 1e6})
      expect_certified_in_bottleneck_units(a, b, q, "trial " + std::to_string(trial));
  }
  for (const bool tangential : {false, true}) {
    const FrameDiagramsPair f8 = lammps_diagrams(8, tangential), f9 = lammps_diagrams(9, tangential);
    for (const double q : {10.0, 1000.0}) {
      expect_certified_in_bottleneck_units(f8.pd0, f9.pd0, q, "pd0 8->9");
      expect_certified_in_bottleneck_units(f8.pd1, f9.pd1, q, "pd1 8->9");
    }
  }
}

// 20 000 points per diagram: the certificate is the only exact check available at that size.
TEST(DistanceDualCertificate, TwentyThousandPointsPerDiagram) {
  std::mt19937_64 rng(12);
  const Diagram a = scaled(random_diagram(rng, 20000, 5, false), 0.125);
  const Diagram b = perturbed(rng, a, 0.00125);
  const auto start = std::chrono::steady_clock::now();
  expect_certified(a, b, 1, "20 000 points");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("seconds", std::to_string(seconds));
}

}  // namespace
}  // namespace fnet::test
