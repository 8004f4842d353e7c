// The flow's start where no line start is taken: a row reduction and a column step, which leave
// every reduced cost >= 0 and most points of close diagrams matched along tight arcs.
#pragma once

#include <cstddef>

#include "common/distance/flow_state.hpp"
#include "common/distance/hub_arcs.hpp"
#include "common/distance/pair_oracle.hpp"

namespace fnet {

// From the empty flow with zero potentials: each a_i takes its cheapest way out (the diagonal or
// one of its `nearest` nearest points of B) when that is still free, then each b_j left free is
// fed from the diagonal when that is its cheapest way in. Hub streams and box maxima refreshed.
void greedy_start(FlowState& flow, HubArcs& hubs, PairOracle& oracle, std::size_t nearest);

}  // namespace fnet
