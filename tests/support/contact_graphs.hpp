// Contact graphs for the randomized comparisons: planar ones as packings produce them, and
// non-planar ones that exercise 2-cycles and dense clique structure.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace fnet::testing {

struct Graph {
  std::size_t vertex_count = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // simple: no loops, no duplicates
};

// Triangular lattice of rows x cols sites, each bond kept with probability `keep`: planar,
// full of triangles, and with 4-, 5-, 6-cycles where bonds are missing.
Graph triangular_lattice(std::size_t rows, std::size_t cols, double keep, std::mt19937_64& rng);

// Square lattice with each bond kept with probability `keep` and some squares given one diagonal:
// planar, with unfilled 4-cycles (the paper's defects).
Graph square_lattice(std::size_t rows, std::size_t cols, double keep, double diagonal, std::mt19937_64& rng);

// n points uniform in the unit square joined when closer than `radius` (small degree).
Graph random_geometric(std::size_t n, double radius, std::mt19937_64& rng);

// Nested separating triangles: a small disk placed in a face touching its three corners, recursively
// (an Apollonian network), `inserts` times in random faces.
Graph apollonian(std::size_t inserts, std::mt19937_64& rng);

// Erdos-Renyi G(n, p): non-planar as soon as p is large.
Graph random_dense(std::size_t n, double p, std::mt19937_64& rng);

Graph complete(std::size_t n);

// K_{3,3} (non-planar, triangle-free) with `chords` random edges inside its two sides, which add triangles.
Graph bipartite_k33_with_chords(std::size_t chords, std::mt19937_64& rng);

// `hubs` vertices joined to each other and to every vertex of a ring of `ring` vertices: vertices
// of high degree whose neighbour lists meet on every hub-hub and hub-ring edge.
Graph hubs_on_a_ring(std::size_t ring, std::size_t hubs);

// Both graphs side by side (vertices of b shifted past a's).
Graph disjoint_union(const Graph& a, const Graph& b);

}  // namespace fnet::testing
