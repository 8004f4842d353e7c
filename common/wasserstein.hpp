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
  // Unused since the solver generates its arcs implicitly; kept for source compatibility.
  std::size_t neighbours = 0;
};

// Statistics of one solve, for benchmarks and tests.
struct WassersteinStats {
  std::size_t arcs = 0, certificate_rounds = 0, arcs_added = 0, augmentations = 0;
  std::size_t settled = 0, boxes_opened = 0;  // Dijkstra work (implicit solver)
};

// Min-cost flow on the complete bipartite graph plus the diagonal as two hubs, solved by successive
// shortest paths from a row-reduction start; the pair arcs are never stored: each search walks a
// 2-d tree over B with per-box potential bounds (diagonal_flow.hpp). With delta > 0 it stops
// between batches of augmentations once the current matching is certified by the potentials (every
// pair's negative reduced cost charged, found by a pruned tree search). Coordinates are rescaled by a power of two first (exact), so the result is
// scale-invariant to rounding and q-th powers neither overflow nor lose the distance scale.
DistanceResult wasserstein_distance(const Diagram& a, const Diagram& b, const WassersteinParams& params = {},
                                    WassersteinStats* stats = nullptr);

}  // namespace fnet
