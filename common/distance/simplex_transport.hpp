// The Wasserstein transport solved exactly on a sparse candidate graph by the network simplex
// (network_simplex.hpp), then priced against every pair:
//  1. the graph: each point's `nearest` nearest neighbours on the other side under L-infinity, the
//     pairs that beat the diagonal only (c_ij < da_i + db_j, TTK's rule: any other pair is never
//     needed, two diagonal matches cost no more), plus every point's diagonal arcs;
//  2. the simplex from every point on the diagonal, to the graph's optimum;
//  3. pricing: with its potentials, every pair of the complete graph is checked with the 2-d tree
//     over B (dual_certificate.hpp: per row a_i the most negative c_ij - pi(b_j) + pi(a_i)); the
//     rows violating beyond rounding give their `top_arcs` most violated pairs, which join the
//     graph, and the simplex goes on from its basis (step 2). None left: the potentials are a
//     feasible LP dual up to rounding, whose bound equals the flow's cost - the certificate.
// The flow's mates and potentials are written into FlowState (its pi, the same node numbering),
// so that DualCertificate::dual_bound and the matching builder read them as they read the
// shortest-path solver's.
#pragma once

#include <cstddef>
#include <cstdint>

#include "common/distance/dual_certificate.hpp"
#include "common/distance/flow_state.hpp"
#include "common/distance/pair_oracle.hpp"

namespace fnet {

struct SimplexTransportParams {
  std::size_t nearest = 4;       // candidates per point, each side
  std::size_t top_arcs = 6;      // violated pairs added per violating row in a pricing round
  std::size_t max_rounds = 200;  // a safety net: past it the answer is still certified, just weaker
  // The line seed (line_seed.hpp): on each death line with at least this many points on both
  // sides (0: none), the programme's matching is the start and its pairs with their neighbours in
  // rank are candidates; its first band and largest size.
  std::size_t line_min_points = 32;
  std::uint32_t band = 32;
  std::size_t max_band_cells = std::size_t{1} << 26;
  std::uint32_t line_ranks = 0;  // columns either side of a line row's partner, as candidates (0: none)
};

struct SimplexTransportStats {
  std::size_t rounds = 0;  // pricing checks over every pair
  std::size_t pivots = 0, degenerate_pivots = 0;
  std::size_t pair_arcs = 0;  // pair arcs in the final graph
  std::size_t initial_arcs = 0;
  bool certified = false;  // the last check found no violation beyond rounding
};

// Solves from the flow's points; the flow's mates and potentials hold the answer on return.
// accept_ratio > 1: stops after the first round whose matching costs <= accept_ratio times the
// dual bound (certificate.dual_bound(flow)); 1: exact.
void solve_by_simplex(FlowState& flow, PairOracle& oracle, DualCertificate& certificate, double accept_ratio,
                      const SimplexTransportParams& params, SimplexTransportStats& stats);

}  // namespace fnet
