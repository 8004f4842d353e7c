// The independent anchor: PD0 and PD1 of a force network's flag complex computed by GUDHI.
#pragma once

#include <cstddef>
#include <span>

#include "common/topology/force_network.hpp"
#include "common/topology/persistence.hpp"

namespace fnet::testing {

// GUDHI filters by sublevel sets, so every value enters negated: vertices at -f(v) (f(v) = max
// incident edge, 0 if none), edges at -f(e), and expansion(2) puts each triangle at the max of its
// edges, -min f. Persistent cohomology over Z/2 with min_persistence 0 (GUDHI drops zero-length
// intervals itself), then mapped back: birth = -b, death = -d, infinite -> -1.
// Edges may come in any order; vertex ids must be < vertex_count. Counts come from the tree.
// The pipeline is GUDHI's own flag-complex route (a Boost graph, insert_graph, expansion), the
// one Rips_complex uses, so a benchmark timing this function times GUDHI as its users run it.
FrameDiagrams gudhi_persistence(std::size_t vertex_count, std::span<const Edge> edges);

}  // namespace fnet::testing
