#include "common/distance/dual_certificate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fnet {

void DualCertificate::check_pairs(const FlowState& flow, PairOracle& oracle, std::size_t top_arcs) {
  violations_.clear();
  pair_penalty_ = 0;
  for (std::uint32_t i = 0; i < flow.n; ++i) {
    // The smallest c_ij - pi(b_j) below -pi(a_i): negative reduced costs.
    const double pa = flow.pi[i];
    oracle.cheapest_prices(i, top_arcs, -pa, top_);
    if (top_.empty()) continue;
    const double amount = -(top_.front().first + pa);
    pair_penalty_ += amount;
    // Beyond rounding: a real violation, repaired; below it, only counted. Rounding in
    // c + pi(a) - pi(b) is relative to the terms' size, not to 1.
    const std::uint32_t jb = top_.front().second;
    const double size = std::fabs(pa) + std::fabs(flow.pi[flow.node_of_b(jb)]) + flow.cost(i, jb);
    if (amount > params_.violation_tolerance * size)
      for (std::size_t t = 0; t < top_.size(); ++t) violations_.push_back({i, top_[t].second, t == 0 ? amount : 0.0});
  }
  ++rounds_;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> DualCertificate::violated_arcs() const {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> arcs;
  for (const Violation& v : violations_) arcs.push_back({v.row, v.column});
  return arcs;
}

void DualCertificate::repair(FlowState& flow, HubArcs& hubs) {
  for (const Violation& v : violations_) {
    if (v.amount == 0) continue;  // a further arc of a row listed before
    const std::uint32_t i = v.row;
    flow.pi[i] += v.amount;
    pair_penalty_ -= v.amount;
    const std::int64_t mate = flow.mate_a[i];
    if (mate >= 0) {
      flow.mate_b[static_cast<std::size_t>(mate)] = FlowState::kNone;
      hubs.refresh(flow, flow.node_of_b(static_cast<std::uint32_t>(mate)));
    } else if (mate == FlowState::kDiagonal) {
      --flow.a_to_diagonal;
    }
    flow.mate_a[i] = FlowState::kNone;
    hubs.refresh(flow, i);
    ++repaired_;
  }
  violations_.clear();
}

double DualCertificate::dual_bound(const FlowState& flow) const {
  // LP duality on the assignment form (every arc but HA -> HB has capacity 1, which changes
  // nothing as each a_i supplies and each b_j takes one unit): demand * potential minus supply *
  // potential, minus each capacity-1 arc's negative reduced cost. Pairs with c_ij >= da_i + db_j
  // are left out of the problem, which keeps its optimum; the other pair arcs' negative reduced
  // costs are the pair penalty. The hub arcs into a point already matched to the diagonal are
  // never scanned (they only close cycles) and may go negative: charged here.
  const auto& pi = flow.pi;
  double dual = static_cast<double>(flow.n) * pi[flow.hb] - static_cast<double>(flow.m) * pi[flow.ha];
  for (std::uint32_t i = 0; i < flow.n; ++i) dual -= pi[i] + std::max(0.0, -(flow.da[i] + pi[i] - pi[flow.hb]));
  for (std::uint32_t j = 0; j < flow.m; ++j) {
    const double pi_b = pi[flow.node_of_b(j)];
    dual += pi_b - std::max(0.0, -(flow.db[j] + pi[flow.ha] - pi_b));
  }
  // HA -> HB is unbounded: a negative reduced cost there (beyond rounding) voids the bound.
  if (pi[flow.ha] - pi[flow.hb] < -params_.hub_tolerance * (std::fabs(pi[flow.ha]) + std::fabs(pi[flow.hb])))
    return -std::numeric_limits<double>::infinity();
  return dual - pair_penalty_;
}

}  // namespace fnet
