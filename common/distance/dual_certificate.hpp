// The LP dual of the flow as its optimality certificate. dual_bound() is a lower bound on the
// optimal cost from the current potentials, valid whatever they are: the pair arcs whose reduced
// cost is negative are charged to it (pair_penalty, found by check_pairs over every pair with the
// 2-d tree), the hub arcs likewise. After an exact solve it equals the flow's cost up to rounding.
// A check lists the rows violating beyond rounding; repair() raises each one's potential to
// feasible and frees it (with its partner) for the searches to route again.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "common/distance/diagonal_flow_params.hpp"
#include "common/distance/flow_state.hpp"
#include "common/distance/hub_arcs.hpp"
#include "common/distance/pair_oracle.hpp"

namespace fnet {

class DualCertificate {
 public:
  struct Violation {
    std::uint32_t row, column;
    double amount;  // -(reduced cost) > 0 for the row's most violated arc; 0 for its further ones
  };

  explicit DualCertificate(const DiagonalFlowParams& params) : params_(params) {}

  // Per row a_i the most negative reduced cost of a pair arc, over every pair (the oracle's box
  // maxima up to date): rows beyond rounding are listed in violations() with their top_arcs most
  // violated arcs, the rest only summed into the pair penalty.
  void check_pairs(const FlowState& flow, PairOracle& oracle, std::size_t top_arcs);
  std::span<const Violation> violations() const { return violations_; }
  // The listed arcs, for the candidates.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> violated_arcs() const;
  void clear_violations() { violations_.clear(); }
  // Raises each listed row's potential by its amount (every pair arc out of it then has reduced
  // cost >= 0, the best one 0) and frees it with its partner; the list is emptied.
  void repair(FlowState& flow, HubArcs& hubs);
  // Every pair arc has reduced cost >= 0 (the searches have scanned them all): no pair penalty.
  void pairs_feasible() { pair_penalty_ = 0; }

  double dual_bound(const FlowState& flow) const;

  std::size_t rounds() const { return rounds_; }      // checks over every pair
  std::size_t repaired() const { return repaired_; }  // rows freed by a violated arc

 private:
  const DiagonalFlowParams& params_;
  std::vector<Violation> violations_;
  double pair_penalty_ = 0;
  std::size_t rounds_ = 0, repaired_ = 0;
  std::vector<std::pair<double, std::uint32_t>> top_;  // a row's most negative c_ij - pi(b_j), ascending
};

}  // namespace fnet
