// compute_persistence_pairs: the simplices behind every diagram point. Their filtration values
// must be the point's birth and death exactly, and where the pairing does not depend on how
// ties are broken it must be the brute-force reduction's (tests/reference).
#include <algorithm>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "common/topology/persistence.hpp"
#include "tests/reference/reference_persistence.hpp"
#include "tests/support/contact_graphs.hpp"
#include "tests/support/diagram_checks.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/random_forces.hpp"

namespace fnet::testing {
namespace {

constexpr ForceKind kKinds[] = {ForceKind::normal, ForceKind::tangential};

std::size_t uniform(std::size_t lo, std::size_t hi, std::mt19937_64& rng) {
  return std::uniform_int_distribution<std::size_t>(lo, hi)(rng);
}

// f on the flag complex, from the network alone.
class Values {
 public:
  explicit Values(const ForceNetwork& net) : vertex_(net.vertex_count, 0.0) {
    for (const Edge& e : net.edges) {
      edge_[{e.u, e.v}] = e.value;
      vertex_[e.u] = std::max(vertex_[e.u], e.value);
      vertex_[e.v] = std::max(vertex_[e.v], e.value);
    }
  }
  // f of the simplex, or nullopt when it is not in the complex.
  std::optional<double> of(const Simplex& s) const {
    const auto& v = s.vertices;
    if (s.size == 1) return v[0] < vertex_.size() ? std::optional(vertex_[v[0]]) : std::nullopt;
    if (s.size == 2) return edge(v[0], v[1]);
    if (s.size == 3) {
      const auto a = edge(v[0], v[1]), b = edge(v[0], v[2]), c = edge(v[1], v[2]);
      if (!a || !b || !c) return std::nullopt;
      return std::min({*a, *b, *c});
    }
    return std::nullopt;
  }
  std::optional<double> edge(std::uint32_t u, std::uint32_t v) const {
    if (!(u < v)) return std::nullopt;
    const auto it = edge_.find({u, v});
    return it == edge_.end() ? std::nullopt : std::optional(it->second);
  }
  bool distinct_edges() const {
    std::set<double> seen;
    for (const auto& [uv, value] : edge_) seen.insert(value);
    return seen.size() == edge_.size();
  }

 private:
  std::map<std::pair<std::uint32_t, std::uint32_t>, double> edge_;
  std::vector<double> vertex_;
};

std::string text(const Simplex& s) {
  std::ostringstream out;
  out << "{";
  for (std::size_t k = 0; k < s.size; ++k) out << (k ? "," : "") << s.vertices[k];
  return out.str() + "}";
}

// Same diagrams as compute_persistence; one pair of simplices per point, of the right
// dimensions, in the complex, with f(birth) == birth and f(death) == death exactly.
::testing::AssertionResult pairs_are_exact(const ForceNetwork& net, const PairedDiagrams& paired) {
  const FrameDiagrams plain = compute_persistence(net);
  if (paired.diagrams.pd0 != plain.pd0 || paired.diagrams.pd1 != plain.pd1)
    return ::testing::AssertionFailure() << "diagrams differ from compute_persistence";
  const Values f(net);
  for (int dim = 0; dim < 2; ++dim) {
    const Diagram& d = dim == 0 ? paired.diagrams.pd0 : paired.diagrams.pd1;
    const auto& s = dim == 0 ? paired.pd0 : paired.pd1;
    if (s.size() != d.size())
      return ::testing::AssertionFailure() << "PD" << dim << ": " << s.size() << " pairs for " << d.size() << " points";
    for (std::size_t k = 0; k < d.size(); ++k) {
      const auto fail = [&] {
        return ::testing::AssertionFailure()
               << "PD" << dim << " point " << k << " (" << d[k].birth << ", " << d[k].death << "): birth "
               << text(s[k].birth) << ", death " << text(s[k].death) << ": ";
      };
      if (s[k].birth.size != dim + 1) return fail() << "birth simplex of the wrong dimension";
      const auto birth = f.of(s[k].birth);
      if (!birth) return fail() << "birth simplex not in the complex";
      if (*birth != d[k].birth) return fail() << "f(birth simplex) = " << *birth;
      if (d[k].death == kNeverDies) {
        if (s[k].death.size != 0) return fail() << "a class that never dies has a death simplex";
        continue;
      }
      if (s[k].death.size != dim + 2) return fail() << "death simplex of the wrong dimension";
      const auto death = f.of(s[k].death);
      if (!death) return fail() << "death simplex not in the complex";
      if (*death != d[k].death) return fail() << "f(death simplex) = " << *death;
    }
  }
  return ::testing::AssertionSuccess();
}

// What of a pair is independent of tie-breaking when all edge values differ: PD0 the birth
// vertex (its partner end of the same edge ties with it; both sides take the lower index) and
// the merging edge; PD1 the edge that closes the loop and the weakest contact of the triangle
// that fills it. The triangle itself is never unique: every triangle whose weakest contact is
// that edge enters at the same value, and which of them is the filler depends on their order.
using Key = std::tuple<std::size_t, std::vector<std::uint32_t>, std::vector<std::uint32_t>>;

std::vector<std::uint32_t> weakest_edge(const std::vector<std::uint32_t>& triangle, const Values& f) {
  std::vector<std::uint32_t> best;
  double value = 0;
  for (std::size_t drop = 0; drop < 3; ++drop) {
    std::vector<std::uint32_t> e;
    for (std::size_t m = 0; m < 3; ++m)
      if (m != drop) e.push_back(triangle[m]);
    const double v = *f.edge(e[0], e[1]);
    if (best.empty() || v < value) best = e, value = v;
  }
  return best;
}

std::vector<Key> fast_keys(const PairedDiagrams& paired, const Values& f) {
  std::vector<Key> keys;
  for (int dim = 0; dim < 2; ++dim) {
    const auto& s = dim == 0 ? paired.pd0 : paired.pd1;
    for (const PointSimplices& p : s) {
      std::vector<std::uint32_t> birth(p.birth.vertices.begin(), p.birth.vertices.begin() + p.birth.size);
      std::vector<std::uint32_t> death(p.death.vertices.begin(), p.death.vertices.begin() + p.death.size);
      if (dim == 1 && !death.empty()) death = weakest_edge(death, f);
      keys.emplace_back(dim, birth, death);
    }
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

std::vector<Key> reference_keys(const Frame& frame, ForceKind kind, double mean, const Values& f) {
  std::vector<Key> keys;
  for (const reference::PairedPoint& p : reference::persistence_pairs(frame, kind, mean)) {
    auto death = p.death_simplex;
    if (p.dimension == 1 && !death.empty()) death = weakest_edge(death, f);
    keys.emplace_back(p.dimension, p.birth_simplex, death);
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

// Exact values always; agreement with the reference when all edge values differ. Returns
// whether the reference comparison applied.
bool check_frame(const Frame& frame, ForceKind kind) {
  const ForceNetwork net = build_network(frame, kind);
  const PairedDiagrams paired = compute_persistence_pairs(net);
  EXPECT_TRUE(pairs_are_exact(net, paired)) << describe(frame);
  const Values f(net);
  if (!f.distinct_edges()) return false;
  EXPECT_EQ(fast_keys(paired, f), reference_keys(frame, kind, net.mean_force, f)) << describe(frame);
  return true;
}

template <class Make>
void check_many(std::uint64_t seed, int count, Make make) {
  std::mt19937_64 rng(seed);
  int compared = 0;
  for (int k = 0; k < count; ++k) {
    const Frame frame = make(rng);
    for (ForceKind kind : kKinds) compared += check_frame(frame, kind);
    if (::testing::Test::HasFailure()) FAIL() << "case " << k << ", seed " << seed;
  }
  EXPECT_GT(compared, count / 2) << "too few frames without ties to compare with the reference";
}

TEST(PersistencePairs, RandomPlanarAndGeometricGraphs) {
  check_many(701, 600, [](auto& rng) {
    const Graph g = uniform(0, 1, rng) == 0 ? triangular_lattice(uniform(2, 6, rng), uniform(2, 6, rng), 0.8, rng)
                                            : square_lattice(uniform(2, 6, rng), uniform(2, 6, rng), 0.9, 0.4, rng);
    return frame_from_graph(g, ForceStyle{}, uniform(0, 2, rng), rng);
  });
}

TEST(PersistencePairs, RandomDenseNonPlanarGraphs) {
  check_many(702, 600, [](auto& rng) {
    return frame_from_graph(random_dense(uniform(4, 11, rng), 0.6, rng), ForceStyle{}, uniform(0, 2, rng), rng);
  });
}

TEST(PersistencePairs, K5AndK33WithChords) {
  check_many(703, 400, [](auto& rng) {
    const Graph g = uniform(0, 1, rng) == 0 ? complete(5) : bipartite_k33_with_chords(uniform(0, 6, rng), rng);
    return frame_from_graph(g, ForceStyle{}, 0, rng);
  });
}

// High-degree vertices take the spilled-list path of the sweep.
TEST(PersistencePairs, HubsOnARing) {
  check_many(704, 60, [](auto& rng) {
    return frame_from_graph(hubs_on_a_ring(uniform(8, 40, rng), uniform(1, 3, rng)), ForceStyle{}, 0, rng);
  });
}

// With ties the pairing is one of several; the values must still be exact.
TEST(PersistencePairs, TiesKeepExactValues) {
  std::mt19937_64 rng(705);
  for (int k = 0; k < 600; ++k) {
    const Graph g = uniform(0, 1, rng) == 0 ? random_dense(uniform(4, 10, rng), 0.6, rng)
                                            : triangular_lattice(uniform(2, 5, rng), uniform(2, 5, rng), 0.85, rng);
    const Frame frame = frame_from_graph(g, random_style(rng), uniform(0, 2, rng), rng);
    for (ForceKind kind : kKinds) {
      const ForceNetwork net = build_network(frame, kind);
      ASSERT_TRUE(pairs_are_exact(net, compute_persistence_pairs(net))) << "case " << k << "\n" << describe(frame);
    }
  }
}

TEST(PersistencePairs, LammpsFrames) {
  const std::size_t n = lammps_frame_count();
  ASSERT_GT(n, 0u);
  int compared = 0;
  for (std::size_t index = 0; index < n; ++index) {
    const Frame frame = lammps_frame(index);
    for (ForceKind kind : kKinds) compared += check_frame(frame, kind);
    ASSERT_FALSE(HasFailure()) << "frame " << index;
  }
  EXPECT_GT(compared, 0);
}

// Rattlers are PD0 points (0, -1) born at their own vertex, after every other point.
TEST(PersistencePairs, RattlersAreTheirOwnBirth) {
  Frame frame;
  frame.label = "rattlers";
  frame.particle_count = 6;
  frame.contacts = {{0, 1, 2.0, 0}, {1, 2, 1.0, 0}, {4, 5, 3.0, 0}};
  const PairedDiagrams p = compute_persistence_pairs(build_network(frame, ForceKind::normal));
  ASSERT_EQ(p.diagrams.pd0.size(), 3u);
  EXPECT_EQ(p.diagrams.pd0.back(), (PersistencePoint{0.0, kNeverDies}));
  EXPECT_EQ(p.pd0.back().birth, (Simplex{{3, 0, 0}, 1}));
  EXPECT_EQ(p.pd0.back().death.size, 0);
}

}  // namespace
}  // namespace fnet::testing
