// The network simplex on candidate arcs with pricing (network_simplex.hpp, simplex_transport.hpp):
// its tree invariants after every solve, its answers against the all-matchings brute force, the
// shortest-path solver and the SciPy assignment oracle, and its LP-dual certificate recomputed
// here over every pair, on hard inputs too (ties everywhere, thousands of identical points, every
// point on one death line, forces spanning 10^12, clouds near the diagonal, empty and one-point
// diagrams); and the WorkDeadline checks in its pivot loop.
#include "common/distance/network_simplex.hpp"

#include <chrono>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "common/distance/diagonal_components.hpp"
#include "common/distance/work_deadline.hpp"
#include "distance_support.hpp"
#include "distance_test_util.hpp"

namespace fnet::test {
namespace {

constexpr WassersteinParams simplex(double q, double delta = 0) {
  return {
      .q = q, .essential = EssentialConvention::floor, .delta = delta, .solver = WassersteinSolver::network_simplex};
}

double cost(PlanePoint a, PlanePoint b, double q) { return std::pow(linf(a, b), q); }

// The bare simplex on small random transport problems, arcs added in batches (as pricing adds
// them): the tree stays consistent and the optimum meets the brute force over the same arcs.
TEST(NetworkSimplex, TreeStaysConsistentAndMeetsBruteForceOnCompleteGraphs) {
  std::mt19937_64 rng(3001);
  std::uniform_int_distribution<int> size(1, 6);
  for (int trial = 0; trial < 300; ++trial) {
    const Diagram da = random_diagram(rng, static_cast<std::size_t>(size(rng)), 3, trial % 3 == 0);
    const Diagram db = random_diagram(rng, static_cast<std::size_t>(size(rng)), 3, trial % 4 == 0);
    const auto a = plane(da), b = plane(db);
    if (a.empty() || b.empty()) continue;
    const double q = trial % 2 ? 2.0 : 1.0;
    std::vector<double> dia, dib;
    for (const PlanePoint p : a) dia.push_back(std::pow(std::fabs(p.x - p.y) / 2, q));
    for (const PlanePoint p : b) dib.push_back(std::pow(std::fabs(p.x - p.y) / 2, q));
    NetworkSimplex ns(dia, dib);
    ASSERT_TRUE(ns.consistent());
    std::vector<std::pair<std::uint32_t, std::uint32_t>> arcs;
    for (std::uint32_t i = 0; i < a.size(); ++i)
      for (std::uint32_t j = 0; j < b.size(); ++j) arcs.push_back({i, j});
    std::shuffle(arcs.begin(), arcs.end(), rng);
    for (std::size_t k = 0; k < arcs.size(); ++k) {
      ns.add_pair_arc(arcs[k].first, arcs[k].second, cost(a[arcs[k].first], b[arcs[k].second], q));
      if (k % 3 == 2 || k + 1 == arcs.size()) {
        ns.solve();
        ASSERT_TRUE(ns.consistent()) << "trial " << trial << " after " << k + 1 << " arcs";
      }
    }
    const auto mate = ns.mates_of_a();
    double total = 0;
    std::vector<int> used(b.size(), 0);
    for (std::uint32_t i = 0; i < a.size(); ++i) {
      if (mate[i] >= 0) {
        ++used[static_cast<std::size_t>(mate[i])];
        total += cost(a[i], b[static_cast<std::size_t>(mate[i])], q);
      } else {
        total += dia[i];
      }
    }
    for (std::size_t j = 0; j < b.size(); ++j) {
      EXPECT_LE(used[j], 1);
      if (!used[j]) total += dib[j];
    }
    const double expected = std::pow(brute_force_distance(da, db, q, EssentialConvention::floor), q);
    EXPECT_NEAR(total, expected, 1e-12 * std::max(1.0, expected)) << "trial " << trial;
  }
}

TEST(NetworkSimplex, WassersteinAgainstBruteForce) {
  std::mt19937_64 rng(3002);
  std::uniform_int_distribution<int> size(0, 7);
  for (int trial = 0; trial < 400; ++trial) {
    const Diagram a = random_diagram(rng, static_cast<std::size_t>(size(rng)), 5, trial % 3 == 0);
    const Diagram b = trial % 2 ? perturbed(rng, a, 0.2)
                                : random_diagram(rng, static_cast<std::size_t>(size(rng)), 5, trial % 5 == 0);
    for (const double q : {1.0, 2.0}) {
      WassersteinStats st;
      const DistanceResult r = wasserstein_distance(a, b, simplex(q), &st);
      const double expected = brute_force_distance(a, b, q, EssentialConvention::floor);
      EXPECT_TRUE(close(r.value, expected, 1e-12))
          << "trial " << trial << " q " << q << ": " << r.value << " vs " << expected;
      EXPECT_TRUE(r.exact);
      EXPECT_TRUE(close(st.dual_lower, r.value, 1e-11) || r.value == 0) << "trial " << trial;
    }
  }
}

void expect_simplex_certified(const Diagram& da, const Diagram& db, double q, const std::string& what) {
  const auto a = plane(da), b = plane(db);
  ASSERT_FALSE(a.empty() || b.empty()) << what;
  const Certificate cert = certify_wasserstein(a, b, q, 1, WassersteinSolver::network_simplex);
  EXPECT_TRUE(cert.matching_valid) << what;
  EXPECT_LE(cert.primal - cert.dual, 1e-11 * std::max(1.0, cert.primal))
      << what << " q=" << q << ": matching " << cert.primal << ", dual bound " << cert.dual;
  EXPECT_LE(cert.dual - cert.primal, 1e-11 * std::max(1.0, cert.primal)) << what << " (weak duality broken)";
  // The public distance through the simplex (rescaled by a power of two) and through the shortest paths.
  WassersteinStats st;
  const DistanceResult r = wasserstein_distance(da, db, simplex(q), &st);
  EXPECT_TRUE(st.network_simplex) << what;
  EXPECT_TRUE(close(r.value, std::pow(cert.primal, 1 / q), 1e-12)) << what << " q=" << q;
  EXPECT_TRUE(close(st.dual_lower, r.value, 1e-11)) << what << " q=" << q;
}

TEST(NetworkSimplex, CertifiedOnRandomAndPerturbedPairs) {
  std::mt19937_64 rng(3003);
  std::uniform_int_distribution<std::size_t> size(1, 400);
  for (int trial = 0; trial < 40; ++trial) {
    const Diagram a = random_diagram(rng, size(rng), 4, trial % 4 == 0);
    const Diagram b = trial % 2 ? perturbed(rng, a, 0.02) : random_diagram(rng, size(rng), 4, trial % 3 == 0);
    for (const double q : {1.0, 2.0}) expect_simplex_certified(a, b, q, "trial " + std::to_string(trial));
  }
}

TEST(NetworkSimplex, AgreesWithShortestPathsAndOracleOnLammpsFrames) {
  for (const bool tangential : {false, true}) {
    const FrameDiagramsPair f8 = lammps_diagrams(8, tangential), f9 = lammps_diagrams(9, tangential);
    for (const auto* d : {&f8.pd0, &f8.pd1}) {
      const Diagram& a = *d;
      const Diagram& b = d == &f8.pd0 ? f9.pd0 : f9.pd1;
      std::vector<double> oracle;
      if (oracle_available()) oracle = oracle_distances(a, b, EssentialConvention::floor, {"1", "2"});
      for (const double q : {1.0, 2.0}) {
        const double ours = wasserstein_distance(a, b, simplex(q)).value;
        const double paths = wasserstein_distance(a, b, {.q = q, .solver = WassersteinSolver::shortest_paths}).value;
        EXPECT_TRUE(close(ours, paths, 1e-12)) << "q " << q << ": " << ours << " vs " << paths;
        if (!oracle.empty()) {
          EXPECT_TRUE(close(ours, oracle[q == 1 ? 0 : 1], 1e-12)) << "oracle q " << q;
        }
        expect_simplex_certified(a, b, q, tangential ? "tangential 8->9" : "normal 8->9");
      }
    }
  }
}

Diagram points_diagram(const std::vector<PlanePoint>& points) {
  Diagram d;
  for (const PlanePoint p : points) d.push_back({p.x, p.y});
  return d;
}

TEST(NetworkSimplex, HardInputsCertified) {
  std::mt19937_64 rng(3004);
  std::uniform_real_distribution<double> u(0, 1);
  // Ten thousand identical points against a few thousand, shifted.
  {
    std::vector<PlanePoint> a(10000, {2.0, 1.0}), b(7000, {2.25, 1.0});
    expect_simplex_certified(points_diagram(a), points_diagram(b), 1, "identical points");
    expect_simplex_certified(points_diagram(a), points_diagram(b), 2, "identical points");
  }
  // Ties everywhere: a coarse grid.
  {
    std::vector<PlanePoint> a, b;
    for (int k = 0; k < 3000; ++k) {
      const double x = std::floor(u(rng) * 8) / 4, y = std::floor(u(rng) * 4) / 4;
      if (x > y) a.push_back({x, y});
      const double x2 = std::floor(u(rng) * 8) / 4, y2 = std::floor(u(rng) * 4) / 4;
      if (x2 > y2) b.push_back({x2, y2});
    }
    for (const double q : {1.0, 2.0}) expect_simplex_certified(points_diagram(a), points_diagram(b), q, "grid ties");
  }
  // Every point on the essential line (floor: death -1 -> 0).
  {
    Diagram a, b;
    for (int k = 0; k < 5000; ++k) a.push_back({u(rng), -1});
    for (int k = 0; k < 5200; ++k) b.push_back({u(rng) * 1.02, -1});
    for (const double q : {1.0, 2.0}) expect_simplex_certified(a, b, q, "all on the line");
  }
  // Forces spanning 10^12.
  {
    Diagram a, b;
    for (int k = 0; k < 3000; ++k) {
      const double scale = std::pow(10.0, -12 * u(rng));
      const double x = scale * (1 + u(rng)), y = x * u(rng);
      a.push_back({x, y});
      b.push_back({x * (1 + 0.01 * u(rng)), y});
    }
    for (const double q : {1.0, 2.0}) expect_simplex_certified(a, b, q, "spanning 1e12");
  }
  // A cloud near the diagonal, far from the origin.
  {
    Diagram a, b;
    for (int k = 0; k < 3000; ++k) {
      const double x = 1000 + u(rng);
      a.push_back({x + 1e-6 * u(rng), x});
      const double x2 = 1000 + u(rng);
      b.push_back({x2 + 1e-6 * u(rng), x2});
    }
    for (const double q : {1.0, 2.0}) expect_simplex_certified(a, b, q, "near-diagonal cloud");
  }
}

TEST(NetworkSimplex, EmptyAndOnePointDiagrams) {
  const Diagram empty, one{{2.0, 1.0}}, other{{2.5, 0.5}};
  for (const double q : {1.0, 2.0}) {
    EXPECT_EQ(wasserstein_distance(empty, empty, simplex(q)).value, 0);
    EXPECT_TRUE(close(wasserstein_distance(one, empty, simplex(q)).value, 0.5, 1e-15));
    EXPECT_TRUE(close(wasserstein_distance(empty, one, simplex(q)).value, 0.5, 1e-15));
    EXPECT_TRUE(close(wasserstein_distance(one, other, simplex(q)).value,
                      brute_force_distance(one, other, q, EssentialConvention::floor), 1e-15));
  }
}

// Large: the certificate recomputed over every pair (2 x 10^8 pairs).
TEST(NetworkSimplex, CertifiedAtTwelveThousandPoints) {
  std::mt19937_64 rng(3005);
  const Diagram a = random_diagram(rng, 12000, 5, false);
  const Diagram b = perturbed(rng, a, 0.002);
  for (const double q : {1.0, 2.0}) expect_simplex_certified(a, b, q, "12 000 points");
}

TEST(NetworkSimplex, ApproximateModeBoundsHold) {
  std::mt19937_64 rng(3006);
  const Diagram a = random_diagram(rng, 6000, 5, false);
  const Diagram b = perturbed(rng, a, 0.01);
  for (const double q : {1.0, 2.0}) {
    const double exact = wasserstein_distance(a, b, simplex(q)).value;
    for (const double delta : {1.0, 0.1, 0.01}) {
      const DistanceResult r = wasserstein_distance(a, b, simplex(q, delta));
      EXPECT_LE(r.lower, exact * (1 + 1e-12)) << "q " << q << " delta " << delta;
      EXPECT_GE(r.upper, exact * (1 - 1e-12)) << "q " << q << " delta " << delta;
      EXPECT_LE(r.upper - r.lower, delta * r.lower * (1 + 1e-12)) << "q " << q << " delta " << delta;
    }
  }
}

// Copies of a diagram moved apart along the diagonal never interact: each copy is a component of
// its own, and the automatic choice gives W2 of such a stack to the simplex, while one diagram
// with a dominant death line keeps the shortest paths' line start.
TEST(NetworkSimplex, DiagonalComponentsAndTheAutomaticChoice) {
  std::mt19937_64 rng(3008);
  const Diagram a = random_diagram(rng, 300, 2, false), b = perturbed(rng, a, 0.01);
  const auto pa = plane(a), pb = plane(b);
  std::vector<PlanePoint> sa, sb;
  for (int copy = 0; copy < 5; ++copy) {
    const double shift = 100.0 * copy;  // far more than any persistence (<= 2)
    for (const PlanePoint p : pa) sa.push_back({p.x + shift, p.y + shift});
    for (const PlanePoint p : pb) sb.push_back({p.x + shift, p.y + shift});
  }
  EXPECT_EQ(largest_diagonal_component(sa, sb), largest_diagonal_component(pa, pb));
  EXPECT_LE(largest_diagonal_component(pa, pb), pa.size() + pb.size());
  // One point whose interval spans the stack joins every copy into one component.
  std::vector<PlanePoint> joined = sa;
  joined.push_back({500, 0});
  EXPECT_EQ(largest_diagonal_component(joined, sb), sa.size() + sb.size() + 1);
  // The stack's distance is the sum of the copies' (q-th powers), through the automatic choice.
  for (const double q : {1.0, 2.0}) {
    WassersteinStats st;
    const double stacked = wasserstein_distance(points_diagram(sa), points_diagram(sb), {.q = q}, &st).value;
    EXPECT_TRUE(st.network_simplex) << "q " << q;
    const double one = wasserstein_distance(a, b, {.q = q, .solver = WassersteinSolver::shortest_paths}).value;
    EXPECT_TRUE(close(stacked, std::pow(5.0, 1 / q) * one, 1e-12)) << "q " << q;
  }
  Diagram line_a, line_b;
  for (int k = 0; k < 2000; ++k) line_a.push_back({1 + std::ldexp(k, -10), -1});
  for (int k = 0; k < 2000; ++k) line_b.push_back({1.01 + std::ldexp(k, -10) * 1.02, -1});
  WassersteinStats st;
  wasserstein_distance(line_a, line_b, {.q = 2}, &st);
  EXPECT_FALSE(st.network_simplex);
  EXPECT_TRUE(st.line_start);
}

TEST(NetworkSimplex, StopsSoonAfterItsWorkDeadline) {
  std::mt19937_64 rng(3007);
  const Diagram a = random_diagram(rng, 20000, 5, false);
  const Diagram b = perturbed(rng, a, 0.01);
  using Clock = std::chrono::steady_clock;
  const auto begin = Clock::now();
  wasserstein_distance(a, b, simplex(1));
  const double unbounded = std::chrono::duration<double>(Clock::now() - begin).count();
  const double budget = unbounded / 20;
  const auto start = Clock::now();
  try {
    const WorkDeadline deadline{std::chrono::duration<double>(budget)};
    wasserstein_distance(a, b, simplex(1));
    ADD_FAILURE() << "finished although its budget was a twentieth of " << unbounded << " s";
  } catch (const WorkDeadlineExceeded& e) {
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), budget + unbounded / 2);
  }
}

}  // namespace
}  // namespace fnet::test
