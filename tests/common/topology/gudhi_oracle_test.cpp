// fnet's PD0 and PD1 against GUDHI's persistent cohomology of the same flag complex.
// The normalization is recomputed here from the raw frame, so build_network is checked too.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/topology/force_network.hpp"
#include "common/topology/persistence.hpp"
#include "tests/support/diagram_match.hpp"
#include "tests/support/gudhi_persistence.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/synthetic_frame.hpp"

namespace fnet::testing {
namespace {

// Values differ from fnet's by the rounding of the mean only (different summation order).
constexpr double kRelative = 1e-12;

// The paper's definition read directly: contacts with |force| > 0, divided by their mean.
std::vector<Edge> normalized_edges(const Frame& frame, ForceKind kind) {
  std::vector<Edge> edges;
  long double sum = 0;
  for (const Contact& c : frame.contacts) {
    const double force = std::fabs(kind == ForceKind::normal ? c.fn : c.ft);
    if (force == 0) continue;
    edges.push_back({static_cast<std::uint32_t>(c.i), static_cast<std::uint32_t>(c.j), force});
    sum += force;
  }
  const double mean = static_cast<double>(sum / static_cast<long double>(edges.size()));
  for (Edge& e : edges) e.value /= mean;
  return edges;
}

void expect_same_as_gudhi(const Frame& frame, ForceKind kind) {
  ASSERT_NO_THROW(validate(frame));
  const FrameDiagrams ours = compute_persistence(build_network(frame, kind));
  const FrameDiagrams gudhi = gudhi_persistence(frame.particle_count, normalized_edges(frame, kind));
  EXPECT_EQ(ours.edges, gudhi.edges);
  EXPECT_EQ(ours.triangles, gudhi.triangles);
  const std::string pd0 = diagram_mismatch(ours.pd0, gudhi.pd0, kRelative);
  const std::string pd1 = diagram_mismatch(ours.pd1, gudhi.pd1, kRelative);
  EXPECT_TRUE(pd0.empty()) << frame.label << ", " << to_string(kind) << " PD0, fnet vs GUDHI: " << pd0;
  EXPECT_TRUE(pd1.empty()) << frame.label << ", " << to_string(kind) << " PD1, fnet vs GUDHI: " << pd1;
}

struct SyntheticCase {
  std::string name;
  SyntheticOptions options;
};

std::vector<SyntheticCase> synthetic_cases() {
  std::vector<SyntheticCase> cases;
  for (std::uint64_t seed = 1; seed <= 6; ++seed)
    cases.push_back({"N2000_seed" + std::to_string(seed), {.particles = 2000, .seed = seed}});
  // Diagrams must not depend on how ties are broken: frames made almost only of ties.
  for (std::uint64_t seed = 1; seed <= 3; ++seed)
    cases.push_back({"N2000_ties_seed" + std::to_string(seed), {.particles = 2000, .seed = seed, .force_levels = 5}});
  // Many K4s: 2-cycles that make triangle columns reduce to zero.
  for (std::uint64_t seed = 1; seed <= 3; ++seed)
    cases.push_back({"N2000_nonplanar_seed" + std::to_string(seed),
                     {.particles = 2000, .seed = seed, .interstitial_fraction = 0.08}});
  cases.push_back({"N20000_seed7", {.particles = 20000, .seed = 7}});
  // Disordered packings, and spheres: tetrahedra and hollow polyhedra (2-cycles) are common in 3D.
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    cases.push_back({"disordered2d_N2000_seed" + std::to_string(seed), disordered_packing(2, 2000, seed)});
    cases.push_back({"disordered3d_N2000_seed" + std::to_string(seed), disordered_packing(3, 2000, seed)});
    cases.push_back({"fcc3d_N2000_seed" + std::to_string(seed), {.particles = 2000, .seed = seed, .dimension = 3}});
  }
  return cases;
}

class SyntheticOracle : public ::testing::TestWithParam<std::tuple<SyntheticCase, ForceKind>> {};

TEST_P(SyntheticOracle, SameDiagramsAsGudhi) {
  const auto& [c, kind] = GetParam();
  expect_same_as_gudhi(synthetic_frame(c.options), kind);
}

std::string kind_name(ForceKind kind) { return std::string(to_string(kind)); }

// The frame after a packing (contacts opened, closed, forces moved): what the distance
// benchmarks measure from.
TEST(SyntheticOracle, TheNextFrameOfAPackingHasTheSameDiagramsAsGudhi) {
  for (const int dimension : {2, 3}) {
    const Frame next = next_frame(synthetic_frame(disordered_packing(dimension, 2000, 3)), {.seed = 3});
    for (const ForceKind kind : {ForceKind::normal, ForceKind::tangential}) expect_same_as_gudhi(next, kind);
  }
}

INSTANTIATE_TEST_SUITE_P(Frames, SyntheticOracle,
                         ::testing::Combine(::testing::ValuesIn(synthetic_cases()),
                                            ::testing::Values(ForceKind::normal, ForceKind::tangential)),
                         [](const auto& test) {
                           return std::get<0>(test.param).name + "_" + kind_name(std::get<1>(test.param));
                         });

// Graphs no packing produces, for the paths a packing never takes: vertices of high degree
// (neighbour lists spill out of line, and long lists meet), cliques of every size (2-cycles
// and beyond), a hub touching everything. Forces are exponential with a share of exact ties.
Frame random_graph_frame(std::size_t n, double p, bool hub, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Frame frame;
  frame.label = "random graph n=" + std::to_string(n) + " p=" + std::to_string(p) + (hub ? " with hub" : "") +
                " seed=" + std::to_string(seed);
  frame.particle_count = n;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!(hub && i == 0) && uniform(rng) >= p) continue;
      Contact c{static_cast<std::int64_t>(j), static_cast<std::int64_t>(i), -std::log1p(-uniform(rng)), 0};
      if (uniform(rng) < 0.1 && !frame.contacts.empty())
        c.fn = frame.contacts[static_cast<std::size_t>(uniform(rng) * static_cast<double>(frame.contacts.size()))].fn;
      c.ft = uniform(rng) < 0.1 ? 0.0 : 0.5 * c.fn * uniform(rng);
      frame.contacts.push_back(c);
    }
  return frame;
}

struct GraphCase {
  std::string name;
  std::size_t n;
  double p;
  bool hub;
  std::uint64_t seed;
};

class GraphOracle : public ::testing::TestWithParam<std::tuple<GraphCase, ForceKind>> {};

TEST_P(GraphOracle, SameDiagramsAsGudhi) {
  const auto& [c, kind] = GetParam();
  expect_same_as_gudhi(random_graph_frame(c.n, c.p, c.hub, c.seed), kind);
}

INSTANTIATE_TEST_SUITE_P(Frames, GraphOracle,
                         ::testing::Combine(::testing::Values(GraphCase{"dense_n70_seed1", 70, 0.4, false, 1},
                                                              GraphCase{"dense_n70_seed2", 70, 0.4, false, 2},
                                                              GraphCase{"dense_n40_seed3", 40, 0.8, false, 3},
                                                              GraphCase{"hub_n600_seed4", 600, 0.01, true, 4},
                                                              GraphCase{"hub_n300_seed5", 300, 0.03, true, 5}),
                                            ::testing::Values(ForceKind::normal, ForceKind::tangential)),
                         [](const auto& test) {
                           return std::get<0>(test.param).name + "_" + kind_name(std::get<1>(test.param));
                         });

class LammpsOracle : public ::testing::TestWithParam<std::tuple<std::size_t, ForceKind>> {};

TEST_P(LammpsOracle, SameDiagramsAsGudhi) {
  const auto& [index, kind] = GetParam();
  ASSERT_LT(index, lammps_frame_count()) << "reference frame missing from tests/data";
  expect_same_as_gudhi(lammps_frame(index), kind);
}

INSTANTIATE_TEST_SUITE_P(Frames, LammpsOracle,
                         ::testing::Combine(::testing::Range<std::size_t>(0, 11),
                                            ::testing::Values(ForceKind::normal, ForceKind::tangential)),
                         [](const auto& test) {
                           return "frame" + std::to_string(std::get<0>(test.param)) + "_" +
                                  kind_name(std::get<1>(test.param));
                         });

}  // namespace
}  // namespace fnet::testing
