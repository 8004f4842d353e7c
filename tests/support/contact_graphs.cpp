#include "tests/support/contact_graphs.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace fnet::testing {
namespace {

bool coin(double p, std::mt19937_64& rng) { return std::bernoulli_distribution(p)(rng); }

void add(Graph& g, std::size_t a, std::size_t b) {
  g.edges.emplace_back(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
}

}  // namespace

Graph triangular_lattice(std::size_t rows, std::size_t cols, double keep, std::mt19937_64& rng) {
  Graph g{rows * cols, {}};
  const auto site = [cols](std::size_t r, std::size_t c) { return r * cols + c; };
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < cols; ++c) {
      if (c + 1 < cols && coin(keep, rng)) add(g, site(r, c), site(r, c + 1));
      if (r + 1 < rows && coin(keep, rng)) add(g, site(r, c), site(r + 1, c));
      if (r + 1 < rows && c + 1 < cols && coin(keep, rng)) add(g, site(r, c), site(r + 1, c + 1));
    }
  return g;
}

Graph square_lattice(std::size_t rows, std::size_t cols, double keep, double diagonal, std::mt19937_64& rng) {
  Graph g{rows * cols, {}};
  const auto site = [cols](std::size_t r, std::size_t c) { return r * cols + c; };
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < cols; ++c) {
      if (c + 1 < cols && coin(keep, rng)) add(g, site(r, c), site(r, c + 1));
      if (r + 1 < rows && coin(keep, rng)) add(g, site(r, c), site(r + 1, c));
      if (r + 1 < rows && c + 1 < cols && coin(diagonal, rng)) {
        if (coin(0.5, rng))
          add(g, site(r, c), site(r + 1, c + 1));
        else
          add(g, site(r, c + 1), site(r + 1, c));
      }
    }
  return g;
}

Graph random_geometric(std::size_t n, double radius, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::array<double, 2>> p(n);
  for (auto& q : p) q = {unit(rng), unit(rng)};
  Graph g{n, {}};
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      if (std::hypot(p[a][0] - p[b][0], p[a][1] - p[b][1]) < radius) add(g, a, b);
  return g;
}

Graph apollonian(std::size_t inserts, std::mt19937_64& rng) {
  Graph g{3, {}};
  add(g, 0, 1), add(g, 1, 2), add(g, 0, 2);
  std::vector<std::array<std::size_t, 3>> faces{{0, 1, 2}};
  for (std::size_t k = 0; k < inserts; ++k) {
    const std::size_t pick = std::uniform_int_distribution<std::size_t>(0, faces.size() - 1)(rng);
    const auto [a, b, c] = faces[pick];
    const std::size_t d = g.vertex_count++;
    add(g, a, d), add(g, b, d), add(g, c, d);
    faces[pick] = {a, b, d};
    faces.push_back({a, c, d});
    faces.push_back({b, c, d});
  }
  return g;
}

Graph random_dense(std::size_t n, double p, std::mt19937_64& rng) {
  Graph g{n, {}};
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      if (coin(p, rng)) add(g, a, b);
  return g;
}

Graph complete(std::size_t n) {
  Graph g{n, {}};
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) add(g, a, b);
  return g;
}

Graph bipartite_k33_with_chords(std::size_t chords, std::mt19937_64& rng) {
  Graph g{6, {}};
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = 3; b < 6; ++b) add(g, a, b);
  // The three possible chords inside each side, chosen without repetition.
  std::vector<std::pair<std::size_t, std::size_t>> inside{{0, 1}, {0, 2}, {1, 2}, {3, 4}, {3, 5}, {4, 5}};
  std::shuffle(inside.begin(), inside.end(), rng);
  for (std::size_t k = 0; k < std::min(chords, inside.size()); ++k) add(g, inside[k].first, inside[k].second);
  return g;
}

Graph hubs_on_a_ring(std::size_t ring, std::size_t hubs) {
  Graph g{ring + hubs, {}};
  for (std::size_t a = 0; a < ring; ++a) add(g, a, (a + 1) % ring);
  for (std::size_t h = ring; h < ring + hubs; ++h) {
    for (std::size_t a = 0; a < ring; ++a) add(g, a, h);
    for (std::size_t other = h + 1; other < ring + hubs; ++other) add(g, h, other);
  }
  return g;
}

Graph disjoint_union(const Graph& a, const Graph& b) {
  Graph g = a;
  g.vertex_count += b.vertex_count;
  for (const auto& [u, v] : b.edges) add(g, u + a.vertex_count, v + a.vertex_count);
  return g;
}

}  // namespace fnet::testing
