#include "common/distance/approximate_stop.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "common/distance/diagonal_flow.hpp"

namespace fnet {

void lower_free_rows(FlowState& flow, PairOracle& oracle) {
  std::vector<std::pair<double, std::uint32_t>> top;
  for (std::uint32_t i = 0; i < flow.n; ++i) {
    if (flow.mate_a[i] != FlowState::kNone) continue;
    const double diagonal = flow.da[i] - flow.pi[flow.hb];  // cost - pi(head) of the arc to the diagonal
    oracle.cheapest_prices(i, 1, diagonal, top);
    flow.pi[i] = -(top.empty() ? diagonal : std::min(diagonal, top.front().first));
  }
}

bool complete_free_rows(FlowState& flow, const CandidateArcs& candidates, double target) {
  if (flow.primal_cost() <= target) return true;
  struct Swap {
    std::uint32_t row, column;
    double cost;
  };
  std::vector<Swap> swaps;
  std::vector<std::uint8_t> used(flow.m, 0);
  double upper = flow.primal_cost();
  for (std::uint32_t i = 0; i < flow.n; ++i) {
    if (flow.mate_a[i] != FlowState::kNone) continue;
    double best_gain = 0;
    Swap best{i, 0, 0};
    for (const std::uint32_t j : candidates.row(i)) {
      if (used[j]) continue;
      const double c = flow.cost(i, j);
      if (!(c < flow.da[i] + flow.db[j])) continue;
      const std::int64_t mate = flow.mate_b[j];
      const double before = flow.da[i] + (mate >= 0 ? flow.mate_cost_a[mate] : flow.db[j]);
      const double after = c + (mate >= 0 ? flow.da[mate] : 0.0);
      if (before - after > best_gain) best_gain = before - after, best = {i, j, c};
    }
    if (best_gain == 0) continue;
    used[best.column] = 1;
    swaps.push_back(best);
    upper -= best_gain;
  }
  if (!(upper <= target)) return false;
  for (const Swap& s : swaps) {
    const std::int64_t mate = flow.mate_b[s.column];
    if (mate >= 0) {
      flow.mate_a[mate] = FlowState::kDiagonal, ++flow.a_to_diagonal;
    } else if (mate == FlowState::kDiagonal) {
      --flow.b_from_diagonal;
    }
    flow.mate_a[s.row] = s.column, flow.mate_b[s.column] = s.row, flow.mate_cost_a[s.row] = s.cost;
  }
  return true;
}

bool match_free_points_apart(FlowState& flow, const DiagonalFlowParams& params, double target) {
  std::vector<PlanePoint> loose_a, loose_b;
  std::vector<std::uint32_t> row_of, column_of;
  double cost_apart = flow.primal_cost();  // loose points counted on the diagonal: replaced below
  for (std::uint32_t i = 0; i < flow.n; ++i)
    if (flow.mate_a[i] < 0) loose_a.push_back(flow.a[i]), row_of.push_back(i), cost_apart -= flow.da[i];
  for (std::uint32_t j = 0; j < flow.m; ++j)
    if (flow.mate_b[j] < 0) loose_b.push_back(flow.b[j]), column_of.push_back(j), cost_apart -= flow.db[j];
  if (loose_a.empty() || loose_b.empty()) return false;  // nothing to pair: the flow's own matching
  DiagonalFlow apart(loose_a, loose_b, flow.power, params);
  apart.solve();
  cost_apart += apart.primal_cost();
  if (!(cost_apart <= target)) return false;
  for (std::uint32_t k = 0; k < row_of.size(); ++k) {
    const std::uint32_t i = row_of[k];
    if (flow.mate_a[i] == FlowState::kDiagonal) --flow.a_to_diagonal;
    const std::int64_t j = apart.mate_of_a(k);
    if (j >= 0) {
      const std::uint32_t column = column_of[static_cast<std::size_t>(j)];
      flow.mate_a[i] = column, flow.mate_cost_a[i] = flow.cost(i, column);
    } else {
      flow.mate_a[i] = FlowState::kDiagonal, ++flow.a_to_diagonal;
    }
  }
  for (std::uint32_t k = 0; k < column_of.size(); ++k) {
    const std::uint32_t j = column_of[k];
    if (flow.mate_b[j] == FlowState::kDiagonal) --flow.b_from_diagonal;
    const std::int64_t i = apart.mate_of_b(k);
    if (i >= 0) {
      flow.mate_b[j] = row_of[static_cast<std::size_t>(i)];
    } else {
      flow.mate_b[j] = FlowState::kDiagonal, ++flow.b_from_diagonal;
    }
  }
  return true;
}

}  // namespace fnet
