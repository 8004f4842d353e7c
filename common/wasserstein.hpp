// Wasserstein distance d_Wq between persistence diagrams, for any real q >= 1: L-infinity ground
// metric, any point may go to the diagonal at (birth - death) / 2, d_Wq = (min sum cost^q)^(1/q).
// Exact by default; with delta > 0 it stops as soon as a matching is certified within delta.
#pragma once

#include <cstddef>

#include "common/diagram.hpp"
#include "common/distance_result.hpp"
#include "common/essential_convention.hpp"

namespace fnet {

struct WassersteinParams {
  double q = 1;  // finite, >= 1
  EssentialConvention essential = EssentialConvention::floor;
  // 0: exact. delta > 0: returns the cost of an actual matching (value == upper) once
  // upper - lower <= delta * lower, lower coming from a feasible dual.
  double delta = 0;
  // Candidate arcs per point (k nearest in L-infinity, both ways); 0 picks a default. Only speed
  // depends on it: the optimality certificate adds whatever arcs the optimum needs.
  std::size_t neighbours = 0;
};

// Statistics of one solve, for benchmarks and tests.
struct WassersteinStats {
  std::size_t arcs = 0, certificate_rounds = 0, arcs_added = 0, augmentations = 0;
};

// Min-cost flow on a sparse candidate graph (k nearest neighbours + the diagonal as two hubs),
// solved by successive shortest paths; then every pair (a, b) is checked for a negative reduced
// cost with a pruned 2-d tree search, the violating arcs are added and the flow re-solved warm,
// until none is left. Coordinates are rescaled by a power of two first (exact), so the result is
// scale-invariant to rounding and q-th powers neither overflow nor lose the distance scale.
DistanceResult wasserstein_distance(const Diagram& a, const Diagram& b, const WassersteinParams& params = {},
                                    WassersteinStats* stats = nullptr);

}  // namespace fnet
