// Wasserstein distance d_Wq between persistence diagrams, for any real q >= 1: L-infinity ground
// metric, any point may go to the diagonal at (birth - death) / 2, d_Wq = (min sum cost^q)^(1/q).
// Exact; a requested relative error delta > 0 is met by answering exactly.
#pragma once

#include <cstddef>

#include "common/distance/diagram_matching.hpp"
#include "common/distance/distance_result.hpp"
#include "common/distance/essential_convention.hpp"
#include "common/topology/diagram.hpp"

namespace fnet {

struct WassersteinParams {
  double q = 1;  // finite, >= 1
  EssentialConvention essential = EssentialConvention::floor;
  // Accepted relative error: the answer must satisfy upper - lower <= delta * lower. Answered
  // exactly whatever the value (lower == upper).
  double delta = 0;
};

// Statistics of one solve, for benchmarks and tests.
struct WassersteinStats {
  std::size_t augmentations = 0;
  std::size_t settled = 0, boxes_opened = 0;  // Dijkstra work (implicit solver)
  // d_Wq's lower bound from the solver's final potentials (LP duality): equal to the value up to
  // rounding, an optimality certificate that needs no reference solver.
  double dual_lower = 0;
};

// Min-cost flow on the complete bipartite graph plus the diagonal as two hubs, solved by successive
// shortest paths from a row-reduction start; the pair arcs are never stored: each search walks a
// 2-d tree over B with per-box potential bounds (diagonal_flow.hpp). delta > 0 is accepted and
// answered exactly (lower == upper), see wasserstein.cpp. Lengths are taken in a unit that keeps
// every q-th power of an optimal matching finite and its sum >= 1 (q = 1, 2: a power of two
// near the largest persistence, exact; other q, or when that sum would underflow: the bottleneck
// distance d_B), so for every q the result is scale-invariant to rounding, d_B <= d_Wq <=
// N^(1/q) d_B (N points in all) holds to the last bit, and d_Wq -> d_B as q grows.
//
// matching (optional): receives an optimal matching, every point of a and b in one term, whose
// (sum of length^q)^(1/q) is the value to rounding; empty when the distance is infinite.
DistanceResult wasserstein_distance(const Diagram& a, const Diagram& b, const WassersteinParams& params = {},
                                    WassersteinStats* stats = nullptr, DiagramMatching* matching = nullptr);

}  // namespace fnet
