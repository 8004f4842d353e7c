// The ends of an approximate solve (accept ratio > 1): the dual bound raised where it is cheap,
// then a matching built from the flow in hand, taken when it costs no more than the target
// (accept ratio times the dual bound). A matching taken leaves a flow that the searches cannot go
// on from: it ends the solve.
#pragma once

#include "common/distance/candidate_arcs.hpp"
#include "common/distance/diagonal_flow_params.hpp"
#include "common/distance/flow_state.hpp"
#include "common/distance/pair_oracle.hpp"

namespace fnet {

// Each free row's potential lowered to the least feasible value. A free row has no arc in, so its
// potential is bound only by its arcs out: the least value that keeps them all >= 0 (one of them
// tight) is feasible and raises the dual bound by what the row's cheapest way out costs.
void lower_free_rows(FlowState& flow, PairOracle& oracle);

// Free rows on the diagonal or, where cheaper, on a candidate b_j whose partner goes to the
// diagonal instead (or that leaves the diagonal): the best such change per row, each b_j at most
// once, in row order. Taken (true) when the matching then costs <= target; the flow is left as it
// is when it costs <= target already.
bool complete_free_rows(FlowState& flow, const CandidateArcs& candidates, double target);

// The loose points (free, or on the diagonal) matched among themselves and the diagonal,
// optimally (a solve of their own, with params), the flow's pairs kept; taken (true) when the
// whole matching then costs <= target. After the line start, whose pairs match the line's points
// optimally among themselves, this is near the optimum.
bool match_free_points_apart(FlowState& flow, const DiagonalFlowParams& params, double target);

}  // namespace fnet
