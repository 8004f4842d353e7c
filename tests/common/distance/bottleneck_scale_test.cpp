// The exact bottleneck at sizes brute force cannot reach, checked from the definition
// (explicit_bottleneck.hpp): the value is a candidate, a matching exists there and none at the
// next smaller candidate; and the matching returned attains it. Inputs that exercise each path
// of the solver: sorted sweeps on the line death = 0 with a whole diagram shifting, ties at the
// answer, a huge dynamic range, everything on the diagonal, single points, the approximation.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "common/distance/bottleneck.hpp"
#include "distance_support.hpp"
#include "explicit_bottleneck.hpp"

namespace fnet::test {
namespace {

const EssentialConvention kFloor = EssentialConvention::floor;

// ~95 % never-dying loops (on death = 0 under floor), as PD1 of a packing; births on a grid of
// `grid` steps when grid > 0 (ties everywhere).
Diagram pd1_like(std::mt19937_64& rng, std::size_t n, double grid = 0) {
  std::uniform_real_distribution<double> u(0, 1);
  Diagram d;
  for (std::size_t k = 0; k < n; ++k) {
    double b = u(rng);
    if (grid > 0) b = std::round(b * grid) / grid + 1 / grid;
    d.push_back({b, u(rng) < 0.95 ? kNeverDies : b * u(rng)});
  }
  return d;
}

// The checks, and the matching: every point once, no term longer than the value, `longest`
// one that attains it.
void expect_exact(const Diagram& a, const Diagram& b, const std::string& what, EssentialConvention c = kFloor) {
  DiagramMatching m;
  const DistanceResult r = bottleneck_distance(a, b, {.essential = c}, &m);
  ASSERT_TRUE(std::isfinite(r.value)) << what;
  EXPECT_TRUE(r.exact) << what;
  EXPECT_EQ(r.lower, r.value) << what;
  EXPECT_EQ(r.upper, r.value) << what;
  const BottleneckCheck check = check_bottleneck(apply_convention(a, c).points, apply_convention(b, c).points, r.value);
  EXPECT_TRUE(check.is_candidate) << what << ": " << r.value;
  EXPECT_TRUE(check.feasible) << what << ": no matching at " << r.value;
  EXPECT_TRUE(check.below_infeasible) << what << ": a matching at " << check.below << " < " << r.value;
  std::vector<int> seen_a(a.size(), 0), seen_b(b.size(), 0);
  for (const MatchedPair& p : m.pairs) {
    if (p.a >= 0) ++seen_a[static_cast<std::size_t>(p.a)];
    if (p.b >= 0) ++seen_b[static_cast<std::size_t>(p.b)];
    EXPECT_LE(p.length, r.value) << what;
  }
  EXPECT_EQ(std::count(seen_a.begin(), seen_a.end(), 1), static_cast<std::ptrdiff_t>(a.size())) << what;
  EXPECT_EQ(std::count(seen_b.begin(), seen_b.end(), 1), static_cast<std::ptrdiff_t>(b.size())) << what;
  if (r.value > 0) {
    ASSERT_LT(m.longest, m.pairs.size()) << what;
    EXPECT_EQ(m.pairs[m.longest].length, r.value) << what;
  }
}

// The checker itself: against brute force over all matchings on small random diagrams, so that
// a wrong checker cannot pass a wrong solver.
TEST(BottleneckScale, CheckerAgreesWithBruteForce) {
  std::mt19937_64 rng(101);
  for (int trial = 0; trial < 60; ++trial) {
    const Diagram a = random_diagram(rng, 1 + trial % 6, 3, trial % 2 == 0),
                  b = random_diagram(rng, trial % 7, 3, trial % 3 == 0);
    const double truth = brute_force_distance(a, b, 0, kFloor);
    const BottleneckCheck check =
        check_bottleneck(apply_convention(a, kFloor).points, apply_convention(b, kFloor).points, truth);
    EXPECT_TRUE(check.feasible) << trial;
    EXPECT_TRUE(check.below_infeasible) << trial;
    if (truth > 0) {
      EXPECT_TRUE(check.is_candidate) << trial;
    }
  }
}

TEST(BottleneckScale, LineHeavyPairsWhereTheWholeMatchingShifts) {
  // B a perturbed copy with 3 % dropped and 3 % added near the diagonal: A has more points on the
  // line, so the matching shifts along it by up to the answer (thousands of partners within it).
  for (const std::size_t n : {300u, 2000u, 4000u}) {
    std::mt19937_64 rng(n);
    const Diagram a = pd1_like(rng, n), b = perturbed(rng, a, 0.002);
    expect_exact(a, b, "n=" + std::to_string(n));
    expect_exact(b, a, "swapped n=" + std::to_string(n));
  }
}

TEST(BottleneckScale, PerturbedCopiesOfRandomDiagrams) {
  for (int seed = 0; seed < 4; ++seed) {
    std::mt19937_64 rng(200 + seed);
    const Diagram a = random_diagram(rng, 3000, 5, false), b = perturbed(rng, a, 0.01 * (seed + 1));
    expect_exact(a, b, "seed " + std::to_string(seed));
  }
}

TEST(BottleneckScale, TiesAtTheAnswer) {
  // Births on a grid of step 1/64, B the same grid moved by one step with a few points more: the
  // answer is 1/64 or a multiple, attained by hundreds of pairs at once.
  std::mt19937_64 rng(301);
  const Diagram a = pd1_like(rng, 3000, 64);
  Diagram b = a;
  for (PersistencePoint& p : b) p.birth += 1.0 / 64;
  for (int k = 0; k < 40; ++k) b.push_back({0.5 + k / 64.0, kNeverDies});
  expect_exact(a, b, "shifted grid");
  const Diagram g = random_diagram(rng, 2500, 5, true), h = random_diagram(rng, 2500, 5, true);
  expect_exact(g, h, "random grids");
}

TEST(BottleneckScale, AnswersWhereBothCoordinatesDifferEqually) {
  // Quarter-step grids: many pairs differ by the same amount in birth and death, so the listing
  // of candidate values (a sweep per coordinate) must count those pairs once, in either sweep.
  // Listings that dropped them gave a larger value on 16 of these 30 000 small pairs (0.25 s).
  std::mt19937_64 rng(351);
  for (int trial = 0; trial < 30000; ++trial) {
    const Diagram a = random_diagram(rng, 2 + trial % 6, 3, true), b = random_diagram(rng, 1 + trial % 7, 3, true);
    ASSERT_EQ(bottleneck_distance(a, b).value, brute_force_distance(a, b, 0, kFloor)) << trial;
  }
  // The first of them (brute force: 1; the listing without those pairs: 1.25).
  const Diagram a = {{3, 1.25}, {2.75, 1}, {1, 0.5}, {2.5, kNeverDies}, {2.5, kNeverDies}},
                b = {{2.5, 0.75}, {1.25, 0.5}, {2.75, 1.75}, {1.5, 1}};
  EXPECT_EQ(brute_force_distance(a, b, 0, kFloor), 1);
  EXPECT_EQ(bottleneck_distance(a, b).value, 1);
  for (int trial = 0; trial < 6; ++trial) {
    const Diagram g = random_diagram(rng, 400, 3, true), h = random_diagram(rng, 380, 3, true);
    expect_exact(g, h, "quarter grid " + std::to_string(trial));
  }
}

TEST(BottleneckScale, HugeDynamicRange) {
  // Coordinates from 1e-250 to 1e250: the bisection cannot be over values, only over candidates
  // or bit patterns.
  std::mt19937_64 rng(401);
  std::uniform_real_distribution<double> e(-250, 250), u(0, 1);
  Diagram a;
  for (int k = 0; k < 2000; ++k) {
    const double b = std::pow(10.0, e(rng));
    a.push_back({b, u(rng) < 0.5 ? kNeverDies : b * u(rng)});
  }
  Diagram b;
  for (const PersistencePoint& p : a)
    if (u(rng) > 0.02) b.push_back({p.birth * (1 + 0.01 * u(rng)), p.death});
  expect_exact(a, b, "1e-250..1e250");
  // And one tiny difference among huge values.
  Diagram c = {{1e300, 0}, {3e-300, 1e-300}}, d = {{1e300, 0}, {3e-300, 2e-300}};
  expect_exact(c, d, "tiny among huge");
  EXPECT_EQ(bottleneck_distance(c, d).value, 1e-300);
}

TEST(BottleneckScale, EverythingOnTheDiagonal) {
  Diagram a, b;
  for (int k = 0; k < 5000; ++k) a.push_back({k * 0.001, k * 0.001});
  for (int k = 0; k < 3000; ++k) b.push_back({0, kNeverDies});  // rattlers: (0, 0) under floor
  DiagramMatching m;
  EXPECT_EQ(bottleneck_distance(a, b, {}, &m).value, 0);
  EXPECT_EQ(m.pairs.size(), a.size() + b.size());
  for (const MatchedPair& p : m.pairs) EXPECT_EQ(p.length, 0);
  // Against points off the diagonal: each goes to the diagonal, the farthest decides.
  std::mt19937_64 rng(501);
  const Diagram c = random_diagram(rng, 4000, 5, false);
  EXPECT_EQ(bottleneck_distance(a, c).value, bottleneck_distance(Diagram{}, c).value);
  expect_exact(a, c, "diagonal vs random");
}

TEST(BottleneckScale, SinglePoints) {
  const Diagram none, one = {{3, 1}}, near = {{3.25, 1}}, far = {{9, 8.5}}, line = {{4, kNeverDies}};
  for (const auto& [x, y] : {std::pair{one, none}, {none, one}, {one, near}, {one, far}, {line, one}, {line, none}}) {
    EXPECT_EQ(bottleneck_distance(x, y).value, brute_force_distance(x, y, 0, kFloor));
    expect_exact(x, y, "single");
  }
  EXPECT_EQ(bottleneck_distance(one, near).value, 0.25);
  EXPECT_EQ(bottleneck_distance(one, far).value, 1);
}

TEST(BottleneckScale, RelativeErrorStaysCertified) {
  std::mt19937_64 rng(601);
  const Diagram a = pd1_like(rng, 5000), b = perturbed(rng, a, 0.002);
  const double exact = bottleneck_distance(a, b).value;
  for (const double e : {0.5, 0.1, 0.01, 0.001}) {
    DiagramMatching m;
    const DistanceResult r = bottleneck_distance(a, b, {.relative_error = e}, &m);
    EXPECT_LE(r.lower, exact) << e;
    EXPECT_GE(r.upper, exact) << e;
    EXPECT_LE(r.upper, (1 + e) * r.lower) << e;
    EXPECT_EQ(r.value, r.upper) << e;
    EXPECT_EQ(m.pairs[m.longest].length, r.value) << e;
  }
}

}  // namespace
}  // namespace fnet::test
