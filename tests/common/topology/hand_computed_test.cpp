// Small complexes whose diagrams follow from the definitions by hand. Forces are chosen with a
// mean of exactly 1 (dyadic values summing to the contact count), so the normalized values are the
// raw forces and the expectations are exact. The reference must agree with the hand too.
#include <gtest/gtest.h>

#include "tests/reference/reference_persistence.hpp"
#include "tests/support/diagram_checks.hpp"
#include "tests/support/small_frames.hpp"

namespace fnet::testing {
namespace {

struct Expected {
  Diagram pd0, pd1;
  std::size_t vertices, edges, triangles;
};

void expect_diagrams(const Frame& frame, const Expected& e) {
  for (ForceKind kind : {ForceKind::normal, ForceKind::tangential}) {
    const FrameDiagrams d = fast_path(frame, kind);
    EXPECT_EQ(d.pd0, e.pd0) << to_string(kind);
    EXPECT_EQ(d.pd1, e.pd1) << to_string(kind);
    EXPECT_EQ(d.vertices, e.vertices);
    EXPECT_EQ(d.edges, e.edges);
    EXPECT_EQ(d.triangles, e.triangles);
    const reference::Diagrams r = reference::persistence(frame, kind);
    EXPECT_EQ(r.pd0, e.pd0) << "reference, " << to_string(kind);
    EXPECT_EQ(r.pd1, e.pd1) << "reference, " << to_string(kind);
    EXPECT_EQ(r.triangles, e.triangles) << "reference";
  }
}

// 0-1 (1.75), 1-2 (1.25), 2-3 (0.75), 3-0 (0.25): the loop closes at the fourth edge, 0.25, and no
// triangle ever fills it.
TEST(HandComputed, FourCycleWithoutTriangleHasOneLoopThatNeverDies) {
  expect_diagrams(frame_of(4, {both(0, 1, 1.75), both(1, 2, 1.25), both(2, 3, 0.75), both(3, 0, 0.25)}),
                  {{{1.75, kNeverDies}}, {{0.25, kNeverDies}}, 4, 4, 0});
}

// The loop is born when the weakest edge closes it and the triangle (f = that same edge) fills it
// at once: a zero-length point, not reported.
TEST(HandComputed, TriangleLoopIsBornAndFilledAtTheSameValue) {
  expect_diagrams(frame_of(3, {both(0, 1, 1.5), both(1, 2, 1.0), both(0, 2, 0.5)}), {{{1.5, kNeverDies}}, {}, 3, 3, 1});
}

// Cycle 1.5, 1.25, 1.0, 0.75, diagonal 0-2 at 0.5: the 4-cycle is born at 0.75; at 0.5 the
// diagonal enters and its two triangles (both f = 0.5) fill the 4-cycle and the diagonal's own loop.
TEST(HandComputed, FourCycleWithWeakDiagonalDiesAtTheDiagonal) {
  expect_diagrams(frame_of(4, {both(0, 1, 1.5), both(1, 2, 1.25), both(2, 3, 1.0), both(3, 0, 0.75), both(0, 2, 0.5)}),
                  {{{1.5, kNeverDies}}, {{0.75, 0.5}}, 4, 5, 2});
}

// A diagonal stronger than the cycle edges splits the square into two triangles that fill every
// loop as soon as it closes: nothing in PD1.
TEST(HandComputed, FourCycleWithStrongDiagonalHasNoLoop) {
  expect_diagrams(frame_of(4, {both(0, 1, 1.0), both(1, 2, 0.75), both(2, 3, 0.5), both(3, 0, 0.25), both(0, 2, 2.5)}),
                  {{{2.5, kNeverDies}}, {}, 4, 5, 2});
}

// K4: square 1.75, 1.5, 1.25, 1.0 and diagonals 0-2 (0.375), 1-3 (0.125); mean (5.5 + 0.5) / 6 = 1.
// The square is born at 1.0 and filled at 0.375 by the triangles on 0-2; the loop born with 1-3 is
// filled at once by one of its triangles, and the last triangle closes the 2-sphere (H2, not reported).
TEST(HandComputed, K4SquareFilledByTheFirstDiagonalAndA2CycleAtTheSecond) {
  expect_diagrams(frame_of(4, {both(0, 1, 1.75), both(1, 2, 1.5), both(2, 3, 1.25), both(3, 0, 1.0), both(0, 2, 0.375),
                               both(1, 3, 0.125)}),
                  {{{1.75, kNeverDies}}, {{1.0, 0.375}}, 4, 6, 4});
}

// K4 with a strongest triangle: every loop is filled when it closes.
TEST(HandComputed, K4WithNestedTrianglesHasEmptyPd1) {
  expect_diagrams(frame_of(4, {both(0, 1, 2.0), both(0, 2, 1.5), both(1, 2, 1.0), both(0, 3, 0.75), both(1, 3, 0.5),
                               both(2, 3, 0.25)}),
                  {{{2.0, kNeverDies}}, {}, 4, 6, 4});
}

// Particle 2 touches nobody with force: (0, -1). Particle 3 has only a contact with zero force.
TEST(HandComputed, RattlersGiveZeroMinusOne) {
  expect_diagrams(frame_of(4, {both(0, 1, 1.0), both(1, 3, 0.0)}),
                  {{{1.0, kNeverDies}, {0.0, kNeverDies}, {0.0, kNeverDies}}, {}, 4, 1, 0});
}

// Two strong pairs joined by a weak contact: the younger pair dies at the bridge.
TEST(HandComputed, TwoComponentsMergeAtTheWeakContact) {
  expect_diagrams(frame_of(4, {both(0, 1, 1.75), both(2, 3, 1.0), both(1, 2, 0.25)}),
                  {{{1.75, kNeverDies}, {1.0, 0.25}}, {}, 4, 3, 0});
}

// Two pairs with equal peaks: exactly one of them dies at the bridge, whichever is chosen.
// (Canonical order: equal births sort by death descending, so -1 comes last.)
TEST(HandComputed, EqualPeaksGiveOnePointWhicheverDies) {
  expect_diagrams(frame_of(4, {both(0, 1, 1.25), both(2, 3, 1.25), both(1, 2, 0.5)}),
                  {{{1.25, 0.5}, {1.25, kNeverDies}}, {}, 4, 3, 0});
}

// Normal and tangential networks have their own means: fn = 3, 1 (mean 2), ft = 1, 0 (mean 1).
TEST(HandComputed, NormalAndTangentialNetworksAreNormalizedSeparately) {
  const Frame frame = frame_of(3, {{0, 1, 3.0, 1.0}, {1, 2, 1.0, 0.0}});
  const FrameDiagrams normal = fast_path(frame, ForceKind::normal);
  EXPECT_EQ(normal.pd0, (Diagram{{1.5, kNeverDies}}));
  EXPECT_EQ(normal.edges, 2u);
  const FrameDiagrams tangential = fast_path(frame, ForceKind::tangential);
  EXPECT_EQ(tangential.pd0, (Diagram{{1.0, kNeverDies}, {0.0, kNeverDies}}));
  EXPECT_EQ(tangential.edges, 1u);
}

}  // namespace
}  // namespace fnet::testing
