// The flow's start where most points lie on one death line (floor PD1s): the sorted-birth
// programme's optimal matching of the line's points (sorted_birth_seed.hpp), the off-line points
// left free, with potentials that certify it over every pair.
#pragma once

#include "common/distance/candidate_arcs.hpp"
#include "common/distance/diagonal_flow_params.hpp"
#include "common/distance/dual_certificate.hpp"
#include "common/distance/flow_state.hpp"
#include "common/distance/hub_arcs.hpp"
#include "common/distance/pair_oracle.hpp"
#include "common/distance/sorted_birth_seed.hpp"

namespace fnet {

// From the empty flow: takes the alignment's pairs (a pair that costs more than sending both to
// the diagonal sends both there) and finds potentials by label-correcting sweeps on the candidate
// graph, checked over every pair; violated arcs join the candidates and the potentials come down
// along them, until no arc is violated, or until the lowering stalls on a few rows, which are then
// repaired (their potentials raised, the rows freed for the searches). true: the flow and its
// potentials are in place, feasible on every pair arc, hub streams refreshed. false (the flow
// empty again, its potentials zero, no pair arc violated): a negative cycle (a band that cut the
// programme's optimum off) or no certificate within params.line_rounds rounds.
bool line_start(const LineAlignment& alignment, const DiagonalFlowParams& params, FlowState& flow, HubArcs& hubs,
                PairOracle& oracle, CandidateArcs& candidates, DualCertificate& certificate);

}  // namespace fnet
