// Diagrams whose points come in copies (repeated_points.hpp): the network simplex with counts
// keeps its tree invariants; W1, W2 and the bottleneck between the distinct points equal the
// all-matchings brute force on small diagrams and the shortest-path solver (which never takes
// the distinct route) on larger ones, the bottleneck the explicit check of its definition; and at
// scale the hard cases of ties: a million copies of one point and a million points on a grid of
// 441, against values proved by hand, each answer certified by its LP-dual bound.
#include "common/distance/repeated_points.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "common/distance/bottleneck.hpp"
#include "common/distance/network_simplex.hpp"
#include "common/distance/wasserstein.hpp"
#include "distance_support.hpp"
#include "distance_test_util.hpp"
#include "explicit_bottleneck.hpp"

namespace fnet::test {
namespace {

// Each point of d in 2..max_copies copies, shuffled.
Diagram copies(std::mt19937_64& rng, const Diagram& d, int max_copies) {
  Diagram out;
  for (const PersistencePoint& p : d)
    for (int k = std::uniform_int_distribution<int>(2, max_copies)(rng); k > 0; --k) out.push_back(p);
  std::shuffle(out.begin(), out.end(), rng);
  return out;
}

TEST(RepeatedPoints, DistinctPointsCountEveryInputPointOnce) {
  const std::vector<PlanePoint> points = {{1, 0}, {2, 1}, {1, 0}, {1, 0.5}, {2, 1}, {1, 0}};
  const DistinctPoints d = distinct_points(points);
  ASSERT_EQ(d.points.size(), 3u);
  EXPECT_EQ(d.count, (std::vector<std::uint32_t>{3, 1, 2}));  // (1,0), (1,0.5), (2,1)
  EXPECT_EQ(d.first, (std::vector<std::uint32_t>{0, 3, 4, 6}));
  for (std::size_t k = 0; k < d.points.size(); ++k)
    for (std::uint32_t m = d.first[k]; m < d.first[k + 1]; ++m) {
      EXPECT_EQ(points[d.members[m]].x, d.points[k].x);
      EXPECT_EQ(points[d.members[m]].y, d.points[k].y);
    }
  EXPECT_EQ(count_distinct(points), 3u);
  EXPECT_EQ(count_distinct(std::vector<PlanePoint>{{0.0, 1}, {-0.0, 1}}), 1u) << "-0 == 0";
  EXPECT_EQ(count_distinct({}), 0u);
  EXPECT_TRUE(solve_distinct(points, points));
  EXPECT_FALSE(solve_distinct(std::span(points).first(4), std::span(points).first(4)))
      << "fewer than half the points are copies";
  EXPECT_FALSE(solve_distinct(points, {})) << "an empty side";
}

// The simplex with counts on complete graphs: consistent, and its flow costs what the unit
// simplex on the expanded points costs.
TEST(RepeatedPoints, CountedSimplexMeetsTheUnitSimplexOnTheCopies) {
  std::mt19937_64 rng(4101);
  std::uniform_int_distribution<std::uint32_t> count(1, 5);
  for (int trial = 0; trial < 200; ++trial) {
    const auto a = plane(random_diagram(rng, 1 + trial % 5, 3, trial % 2 == 0));
    const auto b = plane(random_diagram(rng, 1 + trial % 4, 3, trial % 3 == 0));
    if (a.empty() || b.empty()) continue;
    const double q = trial % 2 ? 2.0 : 1.0;
    std::vector<std::uint32_t> ca, cb;
    std::vector<double> da, db, ua, ub;
    std::vector<PlanePoint> ea, eb;
    for (const PlanePoint p : a) {
      ca.push_back(count(rng));
      da.push_back(std::pow(std::fabs(p.x - p.y) / 2, q));
      for (std::uint32_t k = 0; k < ca.back(); ++k) ea.push_back(p), ua.push_back(da.back());
    }
    for (const PlanePoint p : b) {
      cb.push_back(count(rng));
      db.push_back(std::pow(std::fabs(p.x - p.y) / 2, q));
      for (std::uint32_t k = 0; k < cb.back(); ++k) eb.push_back(p), ub.push_back(db.back());
    }
    NetworkSimplex counted(da, db, ca, cb), unit(ua, ub);
    for (std::uint32_t i = 0; i < a.size(); ++i)
      for (std::uint32_t j = 0; j < b.size(); ++j) counted.add_pair_arc(i, j, std::pow(linf(a[i], b[j]), q));
    for (std::uint32_t i = 0; i < ea.size(); ++i)
      for (std::uint32_t j = 0; j < eb.size(); ++j) unit.add_pair_arc(i, j, std::pow(linf(ea[i], eb[j]), q));
    if (trial % 2) counted.price_by_blocks();
    counted.solve();
    unit.solve();
    ASSERT_TRUE(counted.consistent()) << "trial " << trial;
    const auto flow_cost = [](const NetworkSimplex& s, std::span<const PlanePoint> pa, std::span<const PlanePoint> pb,
                              std::vector<std::uint32_t> left_a, std::vector<std::uint32_t> left_b,
                              std::span<const double> to_diag_a, std::span<const double> to_diag_b, double power) {
      double total = 0;
      for (const auto& f : s.pair_flows()) {
        total += f.amount * std::pow(linf(pa[f.i], pb[f.j]), power);
        left_a[f.i] -= f.amount;
        left_b[f.j] -= f.amount;
      }
      for (std::size_t i = 0; i < left_a.size(); ++i) total += left_a[i] * to_diag_a[i];
      for (std::size_t j = 0; j < left_b.size(); ++j) total += left_b[j] * to_diag_b[j];
      return total;
    };
    const double c = flow_cost(counted, a, b, ca, cb, da, db, q);
    const double u = flow_cost(unit, ea, eb, std::vector<std::uint32_t>(ea.size(), 1),
                               std::vector<std::uint32_t>(eb.size(), 1), ua, ub, q);
    EXPECT_NEAR(c, u, 1e-12 * std::max(1.0, u)) << "trial " << trial;
  }
}

TEST(RepeatedPoints, CountsMustBePositiveAndOnePerPoint) {
  const std::vector<double> d = {1, 2};
  const std::vector<std::uint32_t> one = {1}, zero = {1, 0}, two = {2, 3};
  EXPECT_THROW(NetworkSimplex(d, d, one, two), std::invalid_argument);
  EXPECT_THROW(NetworkSimplex(d, d, zero, two), std::invalid_argument);
  EXPECT_NO_THROW(NetworkSimplex(d, d, two, two));
}

// Small diagrams of copies: every distance against the brute force over all matchings.
TEST(RepeatedPoints, DistancesOfCopiesEqualTheBruteForce) {
  std::mt19937_64 rng(4102);
  for (int trial = 0; trial < 150; ++trial) {
    const Diagram a = copies(rng, random_diagram(rng, 1 + trial % 3, 3, trial % 2 == 0), 2);
    const Diagram b = copies(rng, random_diagram(rng, 1 + (trial / 3) % 3, 3, trial % 4 == 0), 2);
    for (const EssentialConvention c : {EssentialConvention::floor, EssentialConvention::sentinel}) {
      for (const double q : {0.0, 1.0, 2.0}) {
        const double expected = brute_force_distance(a, b, q, c);
        const DistanceResult r = distance(a, b, q, c);
        EXPECT_TRUE(close(r.value, expected, 1e-12))
            << "trial " << trial << " " << label(q, c) << ": " << r.value << " against " << expected;
        EXPECT_TRUE(r.exact);
      }
    }
  }
}

// Ties everywhere on a grid, a few thousand points of a few hundred distinct ones: W1 and W2
// against the shortest paths on every point, the bottleneck against its definition.
TEST(RepeatedPoints, TiesEverywhereAgreeWithTheShortestPathsAndTheDefinition) {
  std::mt19937_64 rng(4103);
  std::uniform_int_distribution<int> grid(0, 12);
  for (int trial = 0; trial < 6; ++trial) {
    Diagram a, b;
    for (int k = 0; k < 3000; ++k) {
      const int d = grid(rng), p = grid(rng);
      a.push_back({double(d + p), k % 10 == 0 ? kNeverDies : double(d)});
    }
    for (int k = 0; k < 2800 + 100 * trial; ++k) {
      const int d = grid(rng), p = grid(rng);
      b.push_back({double(d + p) + 0.5 * (trial % 2), k % 9 == 0 ? kNeverDies : double(d)});
    }
    for (const double q : {1.0, 2.0}) {
      WassersteinStats stats;
      const DistanceResult r = wasserstein_distance(a, b, {.q = q}, &stats);
      const DistanceResult paths = wasserstein_distance(a, b, {.q = q, .solver = WassersteinSolver::shortest_paths});
      EXPECT_TRUE(close(r.value, paths.value, 1e-12)) << "trial " << trial << " W" << q;
      EXPECT_TRUE(stats.network_simplex);
      EXPECT_LE(stats.candidate_arcs, 200u * 200) << "solved between the distinct points";
      EXPECT_NEAR(stats.dual_lower, r.value, 1e-12 * r.value) << "certified";
    }
    const double d = bottleneck_distance(a, b).value;
    const BottleneckCheck check = check_bottleneck(plane(a), plane(b), d);
    EXPECT_TRUE(check.is_candidate && check.feasible && check.below_infeasible) << "trial " << trial << ": " << d;
  }
}

// A million copies of one point: A at (3, 1), B at (3.5, 1.5). Pairs cost 0.5, the diagonal 1
// and 1 (L-infinity: half the persistence): every pair is matched, W_q = n^(1/q) / 2, d_B = 0.5.
// With 1 000 fewer in B, those of A go to the diagonal at 1 each.
TEST(RepeatedPoints, AMillionCopiesOfOnePointAgainstTheValuesByHand) {
  const std::size_t n = 1000000;
  const Diagram a(n, {3, 1}), b(n, {3.5, 1.5}), fewer(n - 1000, {3.5, 1.5});
  const auto start = std::chrono::steady_clock::now();
  for (const double q : {1.0, 2.0}) {
    WassersteinStats stats;
    const DistanceResult r = wasserstein_distance(a, b, {.q = q}, &stats);
    EXPECT_EQ(r.value, std::pow(double(n), 1 / q) / 2) << "W" << q;
    EXPECT_EQ(stats.dual_lower, r.value) << "certified";
    const DistanceResult s = wasserstein_distance(a, fewer, {.q = q}, &stats);
    const double expected = std::pow((n - 1000) * std::pow(0.5, q) + 1000, 1 / q);
    EXPECT_NEAR(s.value, expected, 1e-14 * expected) << "W" << q;
    EXPECT_NEAR(stats.dual_lower, s.value, 1e-14 * s.value) << "certified";
    EXPECT_EQ(wasserstein_distance(a, a, {.q = q}).value, 0);
  }
  EXPECT_EQ(bottleneck_distance(a, b).value, 0.5);
  EXPECT_EQ(bottleneck_distance(a, fewer).value, 1.0);
  EXPECT_EQ(bottleneck_distance(a, a).value, 0.0);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 60);
}

// A million points on a grid of 21 x 21 (deaths 0..20, persistence 100..120), B = A shuffled,
// then B's births moved up by 1. By hand: the shuffle is at distance 0; after the move, W1 = n
// (the dual u(a) = -birth, v(b) = birth, hubs 0, is feasible: pairs by birth differences, the
// diagonal at >= 50 above every potential, and it sums to n), W2 = sqrt(n) (Cauchy-Schwarz on the
// pairs' birth differences, which sum to at least n - 42 k when k points of each side go to the
// diagonal at >= 50^2 each) and d_B = 1 (B's largest birth is 1 past A's, and no length between 0
// and 1 exists on the grid).
TEST(RepeatedPoints, AMillionPointsWithTiesEverywhereAgainstTheValuesByHand) {
  const std::size_t n = 1000000;
  std::mt19937_64 rng(4104);
  std::uniform_int_distribution<int> u(0, 20);
  Diagram a;
  for (std::size_t k = 0; k < n; ++k) {
    const int d = u(rng), p = 100 + u(rng);
    a.push_back({double(d + p), double(d)});
  }
  Diagram b = a;
  std::shuffle(b.begin(), b.end(), rng);
  const auto start = std::chrono::steady_clock::now();
  for (const double q : {0.0, 1.0, 2.0}) EXPECT_EQ(distance(a, b, q, EssentialConvention::floor).value, 0);
  for (PersistencePoint& p : b) p.birth += 1;
  for (const double q : {1.0, 2.0}) {
    WassersteinStats stats;
    const DistanceResult r = wasserstein_distance(a, b, {.q = q}, &stats);
    const double expected = std::pow(double(n), 1 / q);
    EXPECT_NEAR(r.value, expected, 1e-13 * expected) << "W" << q;
    EXPECT_NEAR(stats.dual_lower, r.value, 1e-13 * r.value) << "certified";
  }
  EXPECT_EQ(bottleneck_distance(a, b).value, 1.0);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 120);
}

}  // namespace
}  // namespace fnet::test
