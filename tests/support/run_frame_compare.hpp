// Bit-for-bit comparison of two RunFrames (header, label, every particle, contact and wall
// contact), for the tests of the outputs that must carry frames unchanged: DDS and the run file.
#pragma once

#include <cstring>

#include <gtest/gtest.h>

#include "common/run/run_frame.hpp"

namespace fnet::testing {

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

inline void expect_bit_exact(const RunFrame& want, const RunFrame& got) {
  EXPECT_EQ(want.header, got.header);
  EXPECT_EQ(want.frame.label, got.frame.label);
  ASSERT_EQ(want.frame.particle_count, got.frame.particle_count);
  ASSERT_EQ(want.frame.dimension, got.frame.dimension);
  ASSERT_EQ(want.frame.particles.size(), got.frame.particles.size());
  for (std::size_t k = 0; k < want.frame.particles.size(); ++k) {
    const auto &a = want.frame.particles[k], &b = got.frame.particles[k];
    ASSERT_TRUE(same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z) && same_bits(a.r, b.r))
        << "particle " << k;
  }
  ASSERT_EQ(want.frame.contacts.size(), got.frame.contacts.size());
  for (std::size_t k = 0; k < want.frame.contacts.size(); ++k) {
    const auto &a = want.frame.contacts[k], &b = got.frame.contacts[k];
    ASSERT_TRUE(a.i == b.i && a.j == b.j && same_bits(a.fn, b.fn) && same_bits(a.ft, b.ft)) << "contact " << k;
  }
  EXPECT_EQ(want.wall_contacts, got.wall_contacts);
}

}  // namespace fnet::testing
