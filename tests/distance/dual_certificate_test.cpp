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
#include <gtest/gtest.h>

#include <chrono>

#include "common/diagonal_flow.hpp"
#include "distance_support.hpp"
#include "distance_test_util.hpp"

namespace fnet::test {
namespace {

struct Certificate {
  double primal = 0, dual = 0;
  bool matching_valid = true;
};

double power(double x, double q) { return q == 1 ? x : q == 2 ? x * x : std::pow(x, q); }

Certificate certify(const std::vector<PlanePoint>& a, const std::vector<PlanePoint>& b, double q) {
  std::vector<double> da, db;
  for (const PlanePoint p : a) da.push_back(power(std::fabs(p.x - p.y) / 2, q));
  for (const PlanePoint p : b) db.push_back(power(std::fabs(p.x - p.y) / 2, q));
  DiagonalFlow flow(da, db, a, b, q);
  flow.solve();
  const std::size_t n = a.size(), m = b.size();
  const auto pi = flow.potentials();
  const double ha = pi[n + m], hb = pi[n + m + 1];
  Certificate cert;
  // The matching, from the mates alone.
  std::vector<int> used(m, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t j = flow.mate_of_a(static_cast<std::uint32_t>(i));
    if (j >= 0) {
      cert.matching_valid &= ++used[static_cast<std::size_t>(j)] == 1;
      cert.primal += power(linf_distance(a[i], b[static_cast<std::size_t>(j)]), q);
    } else {
      cert.matching_valid &= j == DiagonalFlow::kDiagonal;
      cert.primal += da[i];
    }
  }
  for (std::size_t j = 0; j < m; ++j)
    if (!used[j]) cert.primal += db[j];
  // The dual bound, every arc scanned.
  double dual = static_cast<double>(n) * hb - static_cast<double>(m) * ha;
  for (std::size_t i = 0; i < n; ++i) dual -= pi[i] + std::max(0.0, -(da[i] + pi[i] - hb));
  for (std::size_t j = 0; j < m; ++j) dual += pi[n + j] - std::max(0.0, -(db[j] + ha - pi[n + j]));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < m; ++j) {
      const double c = power(linf_distance(a[i], b[j]), q);
      if (c < da[i] + db[j]) dual -= std::max(0.0, -(c + pi[i] - pi[n + j]));
    }
  cert.dual = ha >= hb - 1e-12 ? dual : -std::numeric_limits<double>::infinity();
  return cert;
}

std::vector<PlanePoint> plane(const Diagram& d) { return apply_convention(d, EssentialConvention::floor).points; }

void expect_certified(const Diagram& da, const Diagram& db, double q, const std::string& what) {
  const std::vector<PlanePoint> a = plane(da), b = plane(db);
  if (a.empty() || b.empty()) return;
  const Certificate cert = certify(a, b, q);
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

// The solver as wasserstein_distance runs it, on 20 000 points per diagram: the certificate is
// the only exact check available at that size. Coordinates below 1 keep the q-th powers in range
// the way the distance's own rescaling does.
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
