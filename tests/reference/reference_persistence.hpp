// Brute-force PD0 and PD1 of a frame: the answer the fast path (common/persistence.hpp) must give.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/topology/diagram.hpp"
#include "common/topology/force_network.hpp"
#include "common/topology/frame.hpp"

namespace fnet::reference {

struct Diagrams {
  Diagram pd0, pd1;  // birth descending, then death descending; zero-length points dropped
  std::size_t vertices = 0, edges = 0, triangles = 0;
  double mean_force = 0;  // the mean the values were normalized by
};

// Builds the filtration from the frame, reduces the full boundary matrix, and reads the pairs:
// (f(positive simplex), f(negative simplex)); positive simplices never paired get death -1.
Diagrams persistence(const Frame& frame, ForceKind kind);

// The same, normalized by a given mean instead of the reference's own (see flag_filtration).
Diagrams persistence(const Frame& frame, ForceKind kind, double mean);

// A point of positive persistence with the simplices the reduction pairs it by: the positive
// simplex (row) and the negative one (column), as vertex lists; death empty for a class that
// never dies. Ties are broken by the reference's own total order (flag_filtration.cpp).
struct PairedPoint {
  std::size_t dimension = 0;
  double birth = 0, death = 0;
  std::vector<std::uint32_t> birth_simplex, death_simplex;
};

// Every point of PD0 and PD1, in no particular order, normalized by `mean`.
std::vector<PairedPoint> persistence_pairs(const Frame& frame, ForceKind kind, double mean);

}  // namespace fnet::reference
