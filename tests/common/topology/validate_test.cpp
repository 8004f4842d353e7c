// Every rejection of fnet::validate, with its message: it must name the frame and the offending entry.
#include <cmath>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/topology/frame.hpp"

namespace fnet {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Four particles, a valid frame: each test breaks exactly one thing.
Frame valid_frame() {
  Frame f;
  f.label = "frame 12";
  f.particle_count = 4;
  f.particles = {{0, 0, 0.5}, {1, 0, 0.5}, {0, 1, 0.5}, {1, 1, 0.5}};
  f.contacts = {{0, 1, 1.0, 0.1}, {1, 3, 2.0, 0.2}, {2, 3, -0.5, 0.0}, {0, 2, 0.0, 0.3}};
  return f;
}

std::string rejection(const Frame& frame) {
  try {
    validate(frame);
  } catch (const FrameError& e) {
    return e.what();
  }
  return "<accepted>";
}

TEST(Validate, TheBaseFrameIsValid) { EXPECT_NO_THROW(validate(valid_frame())); }

TEST(Validate, FrameWithoutContactsIsValid) {
  Frame f = valid_frame();
  f.contacts.clear();
  EXPECT_NO_THROW(validate(f));
  f.particles.clear();  // and without a particle table
  EXPECT_NO_THROW(validate(f));
  EXPECT_NO_THROW(validate(Frame{}));  // nothing at all
}

TEST(Validate, FrameWithoutParticleTableIsValid) {
  Frame f = valid_frame();
  f.particles.clear();
  EXPECT_NO_THROW(validate(f));
}

TEST(Validate, RejectsNonFiniteNormalForce) {
  for (double bad : {kNaN, kInf, -kInf}) {
    Frame f = valid_frame();
    f.contacts[2].fn = bad;
    EXPECT_THAT(rejection(f),
                AllOf(StartsWith("frame 12: "), HasSubstr("contact 2 (i=2, j=3"), HasSubstr("non-finite")));
  }
}

TEST(Validate, RejectsNonFiniteTangentialForce) {
  for (double bad : {kNaN, kInf, -kInf}) {
    Frame f = valid_frame();
    f.contacts[1].ft = bad;
    EXPECT_THAT(rejection(f),
                AllOf(StartsWith("frame 12: "), HasSubstr("contact 1 (i=1, j=3"), HasSubstr("non-finite")));
  }
}

TEST(Validate, RejectsNonFinitePosition) {
  for (double bad : {kNaN, kInf, -kInf}) {
    Frame fx = valid_frame();
    fx.particles[1].x = bad;
    EXPECT_THAT(rejection(fx), AllOf(StartsWith("frame 12: "), HasSubstr("particle 1"), HasSubstr("non-finite")));
    Frame fy = valid_frame();
    fy.particles[2].y = bad;
    EXPECT_THAT(rejection(fy), AllOf(StartsWith("frame 12: "), HasSubstr("particle 2"), HasSubstr("non-finite")));
  }
}

TEST(Validate, AThreeDimensionalFrameIsValidAndItsZIsChecked) {
  Frame f = valid_frame();
  f.dimension = 3;
  f.particles[0].z = 1.0;
  f.particles[3].z = -2.5;
  EXPECT_NO_THROW(validate(f));
  for (double bad : {kNaN, kInf, -kInf}) {
    f.particles[3].z = bad;
    EXPECT_THAT(rejection(f),
                AllOf(StartsWith("frame 12: "), HasSubstr("particle 3"), HasSubstr("z="), HasSubstr("non-finite")));
  }
}

TEST(Validate, RejectsZInATwoDimensionalFrame) {
  Frame f = valid_frame();
  f.particles[2].z = 0.125;
  EXPECT_THAT(rejection(f), AllOf(StartsWith("frame 12: "), HasSubstr("particle 2 (x=0, y=1, z=0.125, r=0.5)"),
                                  HasSubstr("z is not 0 in a 2D frame")));
}

TEST(Validate, RejectsADimensionOtherThanTwoOrThree) {
  for (int bad : {0, 1, 4, -3}) {
    Frame f = valid_frame();
    f.dimension = bad;
    EXPECT_THAT(rejection(f), AllOf(StartsWith("frame 12: "), HasSubstr("dimension " + std::to_string(bad)),
                                    HasSubstr("neither 2 nor 3")));
  }
}

TEST(Validate, RejectsNonFiniteRadius) {
  for (double bad : {kNaN, kInf}) {
    Frame f = valid_frame();
    f.particles[3].r = bad;
    EXPECT_THAT(rejection(f), AllOf(StartsWith("frame 12: "), HasSubstr("particle 3"), HasSubstr("non-finite")));
  }
}

TEST(Validate, RejectsNegativeRadius) {
  Frame f = valid_frame();
  f.particles[3].r = -0.25;
  EXPECT_THAT(rejection(f), AllOf(StartsWith("frame 12: "), HasSubstr("particle 3"), HasSubstr("r=-0.25"),
                                  HasSubstr("negative radius")));
}

TEST(Validate, RejectsNegativeIndex) {
  Frame fi = valid_frame();
  fi.contacts[1].i = -1;
  EXPECT_THAT(rejection(fi),
              AllOf(StartsWith("frame 12: "), HasSubstr("contact 1 (i=-1, j=3"), HasSubstr("out of range")));
  Frame fj = valid_frame();
  fj.contacts[0].j = -7;
  EXPECT_THAT(rejection(fj),
              AllOf(StartsWith("frame 12: "), HasSubstr("contact 0 (i=0, j=-7"), HasSubstr("out of range")));
}

TEST(Validate, RejectsIndexAtOrAboveParticleCount) {
  Frame f = valid_frame();
  f.contacts[3].j = 4;
  EXPECT_THAT(rejection(f),
              AllOf(StartsWith("frame 12: "), HasSubstr("contact 3 (i=0, j=4"), HasSubstr("out of range [0, 4)")));
  Frame g = valid_frame();
  g.contacts[2].i = 1000;
  EXPECT_THAT(rejection(g), AllOf(StartsWith("frame 12: "), HasSubstr("contact 2 (i=1000"), HasSubstr("out of range")));
}

// Without a particle table the count is implied by the largest index, so an index typed wrong
// (5e9) shows up as a particle count too large: the message must still point at the contact.
TEST(Validate, HugeIndexWithoutParticleTableNamesTheContact) {
  Frame f;
  f.label = "frame 12";
  f.contacts = {{0, 1, 1.0, 1.0}, {2, 5'000'000'000, 1.0, 1.0}};
  f.particle_count = implied_particle_count(f.contacts);
  EXPECT_THAT(rejection(f), AllOf(StartsWith("frame 12: "), HasSubstr("contact 1"), HasSubstr("5000000000")));
}

// Without a particle table the grains beyond those in contacts cost a vertex each: a frame may
// declare only so many of them, bounded by its contacts.
TEST(Validate, DeclaredParticleCountWithoutParticleTableIsBoundedByTheContacts) {
  Frame f = valid_frame();
  f.particles.clear();
  const std::size_t declarable = kDeclaredParticlesPerContact * f.contacts.size() + kDeclaredParticlesFloor;
  f.particle_count = declarable;
  EXPECT_NO_THROW(validate(f));
  f.particle_count = declarable + 1;
  EXPECT_THAT(rejection(f), AllOf(StartsWith("frame 12: particle count " + std::to_string(declarable + 1)),
                                  HasSubstr("without a particle table")));
  f.contacts[3].j = static_cast<std::int64_t>(declarable) + 5;  // as read from a contact list
  f.particle_count = implied_particle_count(f.contacts);
  EXPECT_THAT(rejection(f), AllOf(StartsWith("frame 12: contact 3 (i=0, j=" + std::to_string(declarable + 5)),
                                  HasSubstr("implies more than " + std::to_string(declarable) + " particles")));
  f.particles.assign(f.particle_count, Particle{0, 0, 0.5});  // a table that lists them is another matter
  EXPECT_NO_THROW(validate(f));
}

TEST(Validate, RejectsSelfContact) {
  Frame f = valid_frame();
  f.contacts[1].j = 1;
  EXPECT_THAT(rejection(f),
              AllOf(StartsWith("frame 12: "), HasSubstr("contact 1 (i=1, j=1"), HasSubstr("self-contact")));
}

TEST(Validate, RejectsDuplicatePairInTheSameOrder) {
  Frame f = valid_frame();
  f.contacts.push_back({1, 3, 5.0, 0.5});
  EXPECT_THAT(rejection(f),
              AllOf(StartsWith("frame 12: "), HasSubstr("contact 4 (i=1, j=3"), HasSubstr("duplicate of contact 1")));
}

TEST(Validate, RejectsDuplicatePairInReversedOrder) {
  Frame f = valid_frame();
  f.contacts.insert(f.contacts.begin(), {3, 2, 5.0, 0.5});  // row 0; the same pair is now row 3 as (2, 3)
  EXPECT_THAT(rejection(f),
              AllOf(StartsWith("frame 12: "), HasSubstr("contact 3 (i=2, j=3"), HasSubstr("duplicate of contact 0")));
}

TEST(Validate, RejectsParticleTableOfTheWrongSize) {
  Frame f = valid_frame();
  f.particles.pop_back();
  EXPECT_THAT(rejection(f), AllOf(StartsWith("frame 12: "), HasSubstr("particle table has 3 rows"),
                                  HasSubstr("declares 4 particles")));
  Frame g = valid_frame();
  g.particles.push_back({2, 2, 0.5});
  EXPECT_THAT(rejection(g), AllOf(StartsWith("frame 12: "), HasSubstr("particle table has 5 rows")));
}

}  // namespace
}  // namespace fnet
