// Wasserstein distance d_Wq between persistence diagrams, for any real q >= 1: L-infinity ground
// metric, any point may go to the diagonal at (birth - death) / 2, d_Wq = (min sum cost^q)^(1/q).
// Exact by default; with a relative error delta > 0, certified bounds lower <= d_Wq <= upper with
// upper - lower <= delta * lower, value = upper (the cost of an actual matching).
#pragma once

#include <cstddef>

#include "common/distance/diagram_matching.hpp"
#include "common/distance/distance_result.hpp"
#include "common/distance/essential_convention.hpp"
#include "common/topology/diagram.hpp"

namespace fnet {

// Which exact solver (both certified by the same LP dual): automatic picks by size (README).
enum class WassersteinSolver {
  automatic,
  shortest_paths,   // successive shortest paths with the line start (diagonal_flow.hpp)
  network_simplex,  // network simplex on candidate arcs, priced against every pair (simplex_transport.hpp)
};

struct WassersteinParams {
  double q = 1;  // finite, >= 1
  EssentialConvention essential = EssentialConvention::floor;
  // Accepted relative error: the answer satisfies upper - lower <= delta * lower; the solve stops
  // as soon as its bounds reach it (lower == upper when it is exact by then).
  double delta = 0;
  // q = 1 and 2 only: other q always take the shortest paths (their capped costs).
  WassersteinSolver solver = WassersteinSolver::automatic;
};

// Statistics of one solve, for benchmarks and tests.
struct WassersteinStats {
  std::size_t augmentations = 0;
  std::size_t settled = 0, boxes_opened = 0;  // Dijkstra work (implicit solver)
  std::size_t candidate_arcs = 0;             // pair arcs of the sparse stage
  std::size_t certify_rounds = 0;             // LP-dual checks over every pair
  std::size_t repaired_rows = 0;              // rows freed by a violated arc
  bool completed = false;                     // finished by complete-graph searches
  bool line_start = false;                    // started from the line's optimal matching
  bool network_simplex = false;               // solved by the network simplex (pivots, pricing rounds below)
  std::size_t pivots = 0, pricing_rounds = 0;
  // d_Wq's lower bound from the solver's final potentials (LP duality): equal to the value up to
  // rounding, an optimality certificate that needs no reference solver.
  double dual_lower = 0;
};

// Min-cost flow on the complete bipartite graph plus the diagonal as two hubs, solved by successive
// shortest paths on a sparse candidate graph, certified by the LP dual over every pair (rounds of
// added arcs and repaired rows), finished when needed by searches on the complete graph
// (diagonal_flow.hpp). delta > 0 stops at the first round whose bounds are within delta. Lengths are taken in a unit
// that keeps every q-th power of an optimal matching finite and its sum >= 1 (q = 1, 2: a power of two near the largest
// persistence, exact; other q, or when that sum would underflow: the bottleneck distance d_B), so for every q the
// result is scale-invariant to rounding, d_B <= d_Wq <= N^(1/q) d_B (N points in all) holds to the last bit, and d_Wq
// -> d_B as q grows.
//
// matching (optional): receives an optimal matching, every point of a and b in one term, whose
// (sum of length^q)^(1/q) is the value to rounding; empty when the distance is infinite.
DistanceResult wasserstein_distance(const Diagram& a, const Diagram& b, const WassersteinParams& params = {},
                                    WassersteinStats* stats = nullptr, DiagramMatching* matching = nullptr);

}  // namespace fnet
