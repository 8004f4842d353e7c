// Contacts per grain (the contact graph's degeneracy) against its definition computed the slow
// way: remove a grain of least degree among those left, again and again; the largest degree met
// is the degeneracy.
#include "common/topology/contact_degeneracy.hpp"

#include <algorithm>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "tests/support/contact_graphs.hpp"

namespace fnet {
namespace {

Frame frame_of_graph(const testing::Graph& g) {
  Frame f;
  f.particle_count = g.vertex_count;
  for (const auto& [i, j] : g.edges) f.contacts.push_back({i, j, 1.0, 1.0});
  return f;
}

std::size_t degeneracy_by_definition(const testing::Graph& g) {
  std::vector<std::set<std::uint32_t>> adjacent(g.vertex_count);
  for (const auto& [i, j] : g.edges) adjacent[i].insert(j), adjacent[j].insert(i);
  std::vector<bool> left(g.vertex_count, true);
  std::size_t k = 0;
  for (std::size_t removed = 0; removed < g.vertex_count; ++removed) {
    std::size_t best = g.vertex_count, best_degree = 0;
    for (std::size_t v = 0; v < g.vertex_count; ++v) {
      if (!left[v]) continue;
      const auto d = static_cast<std::size_t>(
          std::count_if(adjacent[v].begin(), adjacent[v].end(), [&](std::uint32_t u) { return left[u]; }));
      if (best == g.vertex_count || d < best_degree) best = v, best_degree = d;
    }
    k = std::max(k, best_degree);
    left[best] = false;
  }
  return k;
}

TEST(ContactDegeneracy, KnownGraphs) {
  EXPECT_EQ(contact_degeneracy(frame_of_graph({})), 0u);
  EXPECT_EQ(contact_degeneracy(frame_of_graph({10, {}})), 0u);
  for (const std::size_t n : {2u, 3u, 7u, 30u})
    EXPECT_EQ(contact_degeneracy(frame_of_graph(testing::complete(n))), n - 1);
  // A star: one large grain touching many small ones has one contact per grain.
  testing::Graph star{41, {}};
  for (std::uint32_t k = 1; k <= 40; ++k) star.edges.push_back({0, k});
  EXPECT_EQ(contact_degeneracy(frame_of_graph(star)), 1u);
  // A full triangular lattice: 3 (its corners and edges peel first).
  std::mt19937_64 rng(1);
  EXPECT_EQ(contact_degeneracy(frame_of_graph(testing::triangular_lattice(20, 20, 1.0, rng))), 3u);
}

TEST(ContactDegeneracy, EqualsTheDefinitionOnRandomGraphs) {
  std::mt19937_64 rng(29);
  for (int trial = 0; trial < 40; ++trial) {
    SCOPED_TRACE(trial);
    std::vector<testing::Graph> graphs = {testing::triangular_lattice(8, 9, 0.7, rng),
                                          testing::random_geometric(120, 0.12, rng), testing::apollonian(60, rng),
                                          testing::random_dense(40, 0.05 + 0.02 * trial, rng)};
    for (const testing::Graph& g : graphs)
      EXPECT_EQ(contact_degeneracy(frame_of_graph(g)), degeneracy_by_definition(g));
  }
}

}  // namespace
}  // namespace fnet
