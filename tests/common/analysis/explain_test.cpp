// explain(): a change planted in one corner of a real frame is found there, and an unchanged frame
// has nothing to explain.
#include "common/analysis/explain.hpp"

#include <algorithm>
#include <limits>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "common/codec/explain_json.hpp"
#include "common/codec/explain_table.hpp"
#include "tests/support/fcc_packing.hpp"
#include "tests/support/lammps_frames.hpp"

namespace fnet {
namespace {

constexpr double kEverywhere = std::numeric_limits<double>::infinity();

// z spans everything unless given: in a 2D frame every z is 0.
struct Box {
  double x_lo, x_hi, y_lo, y_hi, z_lo = -kEverywhere, z_hi = kEverywhere;
  bool holds(const std::array<double, 3>& p) const {
    return p[0] >= x_lo && p[0] <= x_hi && p[1] >= y_lo && p[1] <= y_hi && p[2] >= z_lo && p[2] <= z_hi;
  }
};

// A corner of the packing, `fraction` of its extent on each side: lowest x and y, or highest.
Box corner_of(const Frame& frame, double fraction, bool upper_right) {
  double x_lo = std::numeric_limits<double>::infinity(), y_lo = x_lo, x_hi = -x_lo, y_hi = -x_lo;
  for (const Particle& p : frame.particles)
    x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x), y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
  const double w = fraction * (x_hi - x_lo), h = fraction * (y_hi - y_lo);
  if (upper_right) return {x_hi - w, x_hi, y_hi - h, y_hi};
  return {x_lo, x_lo + w, y_lo, y_lo + h};
}
Box lower_left_corner(const Frame& frame, double fraction) { return corner_of(frame, fraction, false); }

// Both grains of the contact inside the box.
bool inside(const Frame& frame, const Contact& c, const Box& box) {
  const Particle &p = frame.particles[c.i], &q = frame.particles[c.j];
  return box.holds({p.x, p.y, p.z}) && box.holds({q.x, q.y, q.z});
}

// The frame with the forces of every contact inside the box multiplied by `factor`.
Frame strengthened(const Frame& frame, const Box& box, double factor, std::size_t& changed) {
  Frame out = frame;
  changed = 0;
  for (Contact& c : out.contacts)
    if (inside(frame, c, box)) c.fn *= factor, c.ft *= factor, ++changed;
  return out;
}

// Every grain of the point's simplices, with its position, lies in the box.
::testing::AssertionResult in_box(const std::optional<ExplainedPoint>& p, const Box& box) {
  if (!p) return ::testing::AssertionSuccess();
  std::vector<const ExplainedSimplex*> simplices{&p->birth_simplex};
  if (p->death_simplex) simplices.push_back(&*p->death_simplex);
  for (const ExplainedSimplex* s : simplices) {
    if (s->positions.size() != s->grains.size()) return ::testing::AssertionFailure() << "positions missing";
    for (std::size_t k = 0; k < s->grains.size(); ++k)
      if (!box.holds(s->positions[k]))
        return ::testing::AssertionFailure()
               << "grain " << s->grains[k] << " at (" << s->positions[k][0] << ", " << s->positions[k][1] << ", "
               << s->positions[k][2] << ") is outside the corner";
  }
  return ::testing::AssertionSuccess();
}

// The strengthened frame's point of the d_B term, its creating and destroying grains, lie in the
// corner, whichever corner was changed. Its partner in the unchanged frame is matched to it in
// diagram space and may lie anywhere (the strongest contact of the whole packing moves into the
// corner: the essential class's birth grain was elsewhere before).
TEST(Explain, APlantedChangeIsFoundInItsCorner) {
  const Frame a = testing::lammps_frame(testing::lammps_frame_count() - 1);
  for (const bool upper_right : {false, true})
    for (const ForceKind force : {ForceKind::normal, ForceKind::tangential})
      for (const int dim : {0, 1}) {
        const Box corner = corner_of(a, 0.25, upper_right);
        std::size_t changed = 0;
        const Frame b = strengthened(a, corner, 3.0, changed);
        ASSERT_GT(changed, 20u) << "the corner holds too few contacts for a cluster";
        const std::string what = std::string(upper_right ? "upper right " : "lower left ") +
                                 std::string(to_string(force)) + " PD" + std::to_string(dim);
        const Explanation e = explain(a, b, {DistanceMetric::bottleneck(), dim, force, EssentialConvention::floor, 3});
        ASSERT_GT(e.distance.value, 0) << what;
        ASSERT_FALSE(e.terms.empty()) << what;
        EXPECT_EQ(e.terms[0].rank, 1u);
        EXPECT_EQ(e.terms[0].cost, e.distance.value) << what << ": the first term attains d_B";
        ASSERT_TRUE(e.terms[0].b) << what << ": the change is a point of the strengthened frame";
        EXPECT_TRUE(in_box(e.terms[0].b, corner)) << what;
        for (std::size_t k = 1; k < e.terms.size(); ++k) EXPECT_LE(e.terms[k].cost, e.terms[k - 1].cost) << what;
      }
}

// The planted change moved the point that d_B matches; each term's points are the frames' own.
TEST(Explain, TermsCarryTheDiagramPointsAndTheirSimplices) {
  const Frame a = testing::lammps_frame(testing::lammps_frame_count() - 1);
  std::size_t changed = 0;
  const Frame b = strengthened(a, lower_left_corner(a, 0.25), 3.0, changed);
  const Explanation e =
      explain(a, b, {DistanceMetric::wasserstein(2), 1, ForceKind::normal, EssentialConvention::floor, 5});
  ASSERT_EQ(e.terms.size(), 5u);
  for (const ExplainedTerm& t : e.terms) {
    for (const auto* p : {&t.a, &t.b}) {
      if (!*p) continue;
      EXPECT_EQ((*p)->birth_simplex.grains.size(), 2u) << "a loop is born with a contact";
      if ((*p)->point.death != kNeverDies) {
        ASSERT_TRUE((*p)->death_simplex);
        EXPECT_EQ((*p)->death_simplex->grains.size(), 3u) << "a loop is filled by a triangle";
      }
    }
  }
}

TEST(Explain, AnUnchangedFrameHasNothingToExplain) {
  const Frame a = testing::lammps_frame(testing::lammps_frame_count() - 1);
  for (const DistanceMetric metric :
       {DistanceMetric::bottleneck(), DistanceMetric::wasserstein(1), DistanceMetric::wasserstein(2)})
    for (const int dim : {0, 1}) {
      const Explanation e = explain(a, a, {metric, dim, ForceKind::normal, EssentialConvention::floor, 4});
      EXPECT_EQ(e.distance.value, 0);
      EXPECT_TRUE(e.terms.empty());
    }
}

// A frame read without its particle table: grain ids, no positions.
TEST(Explain, WithoutParticlesOnlyIds) {
  Frame a = testing::lammps_frame(0);
  a.particles.clear();
  Frame b = a;
  for (Contact& c : b.contacts) c.fn *= 1 + 0.01 * static_cast<double>(c.i % 7);
  const Explanation e =
      explain(a, b, {DistanceMetric::bottleneck(), 0, ForceKind::normal, EssentialConvention::floor, 2});
  ASSERT_FALSE(e.terms.empty());
  for (const ExplainedTerm& t : e.terms)
    for (const auto* p : {&t.a, &t.b})
      if (*p) {
        EXPECT_FALSE((*p)->birth_simplex.grains.empty());
        EXPECT_TRUE((*p)->birth_simplex.positions.empty());
      }
}

TEST(Explain, BadRequestsAreRefused) {
  const Frame a = testing::lammps_frame(0);
  EXPECT_THROW(explain(a, a, {DistanceMetric::bottleneck(), 2, ForceKind::normal, EssentialConvention::floor, 1}),
               std::invalid_argument);
  EXPECT_THROW(explain(a, a, {DistanceMetric::bottleneck(), 1, ForceKind::normal, EssentialConvention::floor, 0}),
               std::invalid_argument);
  Frame bad = a;
  bad.contacts.push_back({0, 0, 1.0, 0.0});
  EXPECT_THROW(explain(a, bad, {DistanceMetric::bottleneck(), 1, ForceKind::normal, EssentialConvention::floor, 1}),
               FrameError);
}

// A 3D packing: the change planted in one corner octant is found there in x, y and z, and every
// position carries its grain's z, in the JSON and the table too.
TEST(Explain, APlantedChangeInA3DFrameIsFoundInItsCornerInZToo) {
  const Frame a = testing::fcc_frame({.cells = 5});
  validate(a);
  // The octant of lowest x and y and highest z, a quarter of the extent each way.
  double lo = kEverywhere, hi = -kEverywhere;
  for (const Particle& p : a.particles) lo = std::min(lo, p.x), hi = std::max(hi, p.x);  // a cube: x = y = z
  const double q = 0.3 * (hi - lo);
  const Box corner{lo, lo + q, lo, lo + q, hi - q, hi};
  std::size_t changed = 0;
  Frame b = strengthened(a, corner, 3.0, changed);
  ASSERT_GT(changed, 20u);
  // Spread the planted forces, so that the corner is not a uniformly scaled copy.
  for (std::size_t n = 0; n < b.contacts.size(); ++n)
    if (inside(a, a.contacts[n], corner)) b.contacts[n].fn *= 1 + 0.05 * static_cast<double>(n % 7);
  for (const int dim : {0, 1}) {
    const ExplainRequest request{DistanceMetric::bottleneck(), dim, ForceKind::normal, EssentialConvention::floor, 3};
    const Explanation e = explain(a, b, request);
    ASSERT_FALSE(e.terms.empty()) << "PD" << dim;
    ASSERT_TRUE(e.terms[0].b) << "PD" << dim;
    EXPECT_TRUE(in_box(e.terms[0].b, corner)) << "PD" << dim;
    EXPECT_EQ(e.terms[0].b->birth_simplex.dimension, 3);
    const nlohmann::json j = explain_json(a, b, request);
    const nlohmann::json& simplex = j["explain"][0]["b"]["birth_simplex"];
    ASSERT_EQ(simplex["positions"].size(), simplex["grains"].size());
    for (std::size_t k = 0; k < simplex["grains"].size(); ++k) {
      const Particle& p = b.particles[simplex["grains"][k].get<std::size_t>()];
      EXPECT_EQ(simplex["positions"][k], nlohmann::json({p.x, p.y, p.z})) << "PD" << dim;
    }
    nlohmann::json answer = j;
    answer["dim"] = dim, answer["force"] = "normal", answer["essential"] = "floor";
    std::ostringstream table;
    write_explain_table(table, answer, "d_B");
    EXPECT_NE(table.str().find("where (x, y, z)"), std::string::npos) << table.str();
  }
}

}  // namespace
}  // namespace fnet
