// The synthetic packings the tests and benchmarks use look like what they stand for: spheres with
// a jammed packing's contact number, and a next frame that differs as a slow compression's does.
#include "tests/support/synthetic_frame.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace fnet::testing {
namespace {

// 2 x contacts carrying a normal force / grains.
double contact_number(const Frame& f) {
  const auto loaded = std::count_if(f.contacts.begin(), f.contacts.end(), [](const Contact& c) { return c.fn > 0; });
  return 2.0 * static_cast<double>(loaded) / static_cast<double>(f.particle_count);
}

std::map<std::pair<std::int64_t, std::int64_t>, Contact> by_pair(const Frame& f) {
  std::map<std::pair<std::int64_t, std::int64_t>, Contact> out;
  for (const Contact& c : f.contacts) out[{std::min(c.i, c.j), std::max(c.i, c.j)}] = c;
  return out;
}

TEST(SyntheticFrame, SpheresHaveAJammedPackingsContactNumber) {
  // 20 000 spheres: a small packing's surface, where grains have fewer neighbours, would count.
  for (const SyntheticOptions& options :
       {disordered_packing(3, 20000, 1), SyntheticOptions{.particles = 20000, .dimension = 3}}) {
    const Frame f = synthetic_frame(options);
    EXPECT_NO_THROW(validate(f));
    EXPECT_EQ(f.dimension, 3);
    const auto [low, high] = std::minmax_element(f.particles.begin(), f.particles.end(),
                                                 [](const Particle& a, const Particle& b) { return a.z < b.z; });
    EXPECT_GT(high->z - low->z, 20);  // about 28 layers
    EXPECT_GT(contact_number(f), 5.5);
    EXPECT_LT(contact_number(f), 6.5);
    for (const Particle& p : f.particles) {
      EXPECT_GE(p.r, 0.4);
      EXPECT_LE(p.r, 0.6);
    }
  }
}

TEST(SyntheticFrame, TheDisorderedDiskPackingHasTheLammpsFramesContactNumber) {
  const Frame f = synthetic_frame(disordered_packing(2, 4000, 1));
  EXPECT_NO_THROW(validate(f));
  EXPECT_EQ(f.dimension, 2);
  for (const Particle& p : f.particles) EXPECT_EQ(p.z, 0);
  EXPECT_NEAR(contact_number(f), 4.16, 0.25);  // tests/data's LAMMPS frame at rho 0.90
}

TEST(SyntheticFrame, TheNextFrameDiffersAsASlowCompressionsDoes) {
  for (const int dimension : {2, 3}) {
    const Frame first = synthetic_frame(disordered_packing(dimension, 4000, 2));
    const Frame next = next_frame(first, {.seed = 5});
    EXPECT_NO_THROW(validate(next));
    EXPECT_EQ(next.dimension, dimension);
    EXPECT_EQ(next.particle_count, first.particle_count);
    const Frame again = next_frame(first, {.seed = 5});
    ASSERT_EQ(again.contacts.size(), next.contacts.size());
    for (std::size_t k = 0; k < next.contacts.size(); ++k) {
      EXPECT_EQ(again.contacts[k].fn, next.contacts[k].fn);
      EXPECT_EQ(again.contacts[k].ft, next.contacts[k].ft);
    }
    const auto before = by_pair(first), after = by_pair(next);
    std::size_t opened = 0, closed = 0, changed_much = 0, kept = 0;
    for (const auto& [pair, c] : before) opened += !after.contains(pair);
    for (const auto& [pair, c] : after) {
      const auto it = before.find(pair);
      if (it == before.end()) {
        ++closed;
      } else if (it->second.fn > 0 && c.fn > 0) {
        ++kept;
        changed_much += std::fabs(c.fn / it->second.fn - 1) > 0.03 + 1e-12;
      }
    }
    const double n = static_cast<double>(before.size());
    SCOPED_TRACE(dimension);
    EXPECT_GT(static_cast<double>(opened) / n, 0.001);
    EXPECT_LT(static_cast<double>(opened) / n, 0.03);
    EXPECT_GT(static_cast<double>(closed) / n, 0.001);
    EXPECT_LT(static_cast<double>(closed) / n, 0.03);
    EXPECT_GT(static_cast<double>(kept) / n, 0.95);
    EXPECT_LT(static_cast<double>(changed_much) / static_cast<double>(kept), 0.01);  // ties and zeros only
  }
}

}  // namespace
}  // namespace fnet::testing
