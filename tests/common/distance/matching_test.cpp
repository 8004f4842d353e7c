// The matching a distance returns: a valid matching (every point exactly once), whose terms have
// the lengths of their points under the convention, and whose cost is the distance itself:
// (sum of length^q)^(1/q) for W_q to rounding, the longest length for d_B exactly.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "common/distance/bottleneck.hpp"
#include "common/distance/diagram_matching.hpp"
#include "common/distance/wasserstein.hpp"
#include "tests/common/distance/distance_support.hpp"
#include "tests/common/distance/distance_test_util.hpp"

namespace fnet::test {
namespace {

// The point as the distance sees it, computed here from the convention's definition.
PlanePoint seen(const PersistencePoint& p, EssentialConvention c) {
  if (p.death == kNeverDies && c == EssentialConvention::floor) return {p.birth, 0};
  return {p.birth, p.death};
}

// Every point of a and of b exactly once; each term's length recomputed from the diagrams.
::testing::AssertionResult valid(const Diagram& a, const Diagram& b, const DiagramMatching& m, EssentialConvention c) {
  std::vector<int> seen_a(a.size(), 0), seen_b(b.size(), 0);
  for (const MatchedPair& t : m.pairs) {
    if (t.a < -1 || t.a >= static_cast<std::int64_t>(a.size()) || t.b < -1 ||
        t.b >= static_cast<std::int64_t>(b.size()) || (t.a < 0 && t.b < 0))
      return ::testing::AssertionFailure() << "term (" << t.a << ", " << t.b << ") out of range";
    if (t.a >= 0) ++seen_a[t.a];
    if (t.b >= 0) ++seen_b[t.b];
    double expected = 0;
    if (t.a >= 0 && t.b >= 0) {
      const PersistencePoint &p = a[t.a], &q = b[t.b];
      const bool ep = p.death == kNeverDies, eq = q.death == kNeverDies;
      if (c == EssentialConvention::separate && ep != eq)
        return ::testing::AssertionFailure() << "separate: a never-dying class matched with a dying one";
      expected = c == EssentialConvention::separate && ep ? std::fabs(p.birth - q.birth) : linf(seen(p, c), seen(q, c));
    } else {
      const PersistencePoint& p = t.a >= 0 ? a[t.a] : b[t.b];
      if (c == EssentialConvention::separate && p.death == kNeverDies)
        return ::testing::AssertionFailure() << "separate: a never-dying class matched with the diagonal";
      const PlanePoint s = seen(p, c);
      expected = std::fabs(s.x - s.y) / 2;
    }
    if (t.length != expected)
      return ::testing::AssertionFailure() << "term (" << t.a << ", " << t.b << ") has length " << t.length
                                           << ", its points are " << expected << " apart";
  }
  for (std::size_t i = 0; i < a.size(); ++i)
    if (seen_a[i] != 1) return ::testing::AssertionFailure() << "point " << i << " of a in " << seen_a[i] << " terms";
  for (std::size_t j = 0; j < b.size(); ++j)
    if (seen_b[j] != 1) return ::testing::AssertionFailure() << "point " << j << " of b in " << seen_b[j] << " terms";
  if (!m.pairs.empty())
    for (const MatchedPair& t : m.pairs)
      if (t.length > m.pairs[m.longest].length) return ::testing::AssertionFailure() << "longest is not the longest";
  return ::testing::AssertionSuccess();
}

// (sum of length^q)^(1/q), summed relative to the longest term.
double cost(const DiagramMatching& m, double q) {
  double top = 0;
  for (const MatchedPair& t : m.pairs) top = std::max(top, t.length);
  if (top == 0) return 0;
  long double sum = 0;
  for (const MatchedPair& t : m.pairs) sum += std::pow(static_cast<long double>(t.length / top), q);
  return static_cast<double>(std::pow(sum, 1 / static_cast<long double>(q))) * top;
}

// The matching of every distance between a and b: W_q for each q given and d_B, under each convention.
// with_plain: also check that the value is the one computed without a matching.
void check_pair(const Diagram& a, const Diagram& b, const std::string& what,
                const std::vector<double>& exponents = {1.0, 2.0, 3.5}, bool with_plain = true) {
  for (const EssentialConvention c : kAllConventions) {
    for (const double q : exponents) {
      DiagramMatching m;
      const DistanceResult d = wasserstein_distance(a, b, {.q = q, .essential = c}, nullptr, &m);
      if (with_plain) {
        ASSERT_EQ(d.value, wasserstein_distance(a, b, {.q = q, .essential = c}).value)
            << what << " " << label(q, c) << ": asking for the matching changed the value";
      }
      if (d.infinite) {
        EXPECT_TRUE(m.pairs.empty()) << what;
        continue;
      }
      ASSERT_TRUE(valid(a, b, m, c)) << what << " " << label(q, c);
      EXPECT_TRUE(close(cost(m, q), d.value, 1e-12))
          << what << " " << label(q, c) << ": matching costs " << cost(m, q) << ", distance " << d.value;
    }
    DiagramMatching m;
    const DistanceResult d = bottleneck_distance(a, b, {.essential = c}, &m);
    ASSERT_EQ(d.value, bottleneck_distance(a, b, {.essential = c}).value) << what;
    if (d.infinite) {
      EXPECT_TRUE(m.pairs.empty()) << what;
      continue;
    }
    ASSERT_TRUE(valid(a, b, m, c)) << what << " " << label(0, c);
    const double longest = m.pairs.empty() ? 0 : m.pairs[m.longest].length;
    EXPECT_EQ(longest, d.value) << what << " " << label(0, c) << ": the attaining term";
    // With a relative error: the matching whose bottleneck is the value returned.
    const DistanceResult approx = bottleneck_distance(a, b, {.essential = c, .relative_error = 0.5}, &m);
    ASSERT_TRUE(valid(a, b, m, c)) << what << " approximate";
    EXPECT_EQ(m.pairs.empty() ? 0 : m.pairs[m.longest].length, approx.value) << what << " approximate";
  }
}

TEST(Matching, RandomDiagrams) {
  std::mt19937_64 rng(801);
  for (int k = 0; k < 300; ++k) {
    const Diagram a = random_diagram(rng, std::uniform_int_distribution<std::size_t>(0, 40)(rng), 3.0, false);
    const Diagram b = k % 2 ? perturbed(rng, a, 0.2)
                            : random_diagram(rng, std::uniform_int_distribution<std::size_t>(0, 40)(rng), 3.0, false);
    check_pair(a, b, "case " + std::to_string(k));
    if (HasFatalFailure()) return;
  }
}

// Coordinates on a coarse grid: ties between lengths everywhere, duplicated points.
TEST(Matching, TieHeavyDiagrams) {
  std::mt19937_64 rng(802);
  for (int k = 0; k < 300; ++k) {
    const Diagram a = random_diagram(rng, std::uniform_int_distribution<std::size_t>(0, 40)(rng), 4.0, true);
    const Diagram b = k % 2 ? perturbed(rng, a, 0.0)
                            : random_diagram(rng, std::uniform_int_distribution<std::size_t>(0, 40)(rng), 4.0, true);
    check_pair(a, b, "case " + std::to_string(k));
    if (HasFatalFailure()) return;
  }
}

// Every point in two to four copies: the distances solve between the distinct points
// (repeated_points.hpp) and split the flow among the copies.
TEST(Matching, CopiesOfPoints) {
  std::mt19937_64 rng(803);
  const auto copies = [&](const Diagram& d) {
    Diagram out;
    for (const PersistencePoint& p : d)
      for (int k = std::uniform_int_distribution<int>(2, 4)(rng); k > 0; --k) out.push_back(p);
    std::shuffle(out.begin(), out.end(), rng);
    return out;
  };
  for (int k = 0; k < 100; ++k) {
    const Diagram a = random_diagram(rng, std::uniform_int_distribution<std::size_t>(1, 12)(rng), 4.0, k % 2 == 0);
    const Diagram b = k % 3 ? perturbed(rng, a, 0.3) : random_diagram(rng, 8, 4.0, k % 2 == 0);
    check_pair(copies(a), copies(b), "case " + std::to_string(k), {1.0, 2.0});
    if (HasFatalFailure()) return;
  }
}

// Consecutive frames, early (few contacts) and late (near jamming, ~1200 loops); W1 and W2, the
// stored metrics (a W_q solve of the late pair takes about a second on a loaded machine).
TEST(Matching, LammpsFramePairs) {
  for (const auto& [frame, tangential] : {std::pair{0, false}, std::pair{0, true}, std::pair{9, false}}) {
    const FrameDiagramsPair x = lammps_diagrams(frame, tangential), y = lammps_diagrams(frame + 1, tangential);
    const std::string what = "frames " + std::to_string(frame) + "->" + std::to_string(frame + 1);
    check_pair(x.pd0, y.pd0, what + " PD0", {1.0, 2.0}, false);
    check_pair(x.pd1, y.pd1, what + " PD1", {1.0, 2.0}, false);
    if (HasFatalFailure()) return;
  }
}

// Equal diagrams (the early exit) and diagrams with points only on the diagonal or a rattler.
TEST(Matching, EqualAndDegenerateDiagrams) {
  const Diagram a = {{2.0, 1.0}, {1.5, kNeverDies}, {0.0, kNeverDies}, {1.0, 1.0}};
  Diagram b = a;
  std::swap(b[0], b[3]);
  check_pair(a, b, "equal");
  check_pair(a, {}, "against empty");
  check_pair({}, {}, "both empty");
  check_pair({{0.0, kNeverDies}}, {{1.0, 1.0}}, "diagonal only");
  DiagramMatching m;
  EXPECT_EQ(wasserstein_distance(a, b, {.q = 1}, nullptr, &m).value, 0);
  for (const MatchedPair& t : m.pairs) EXPECT_EQ(t.length, 0);
}

}  // namespace
}  // namespace fnet::test
