#include "common/distance/line_start.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/distance/work_deadline.hpp"

namespace fnet {

namespace {

constexpr std::int64_t kDiagonal = FlowState::kDiagonal;

// The flow's units in birth order: a matched pair (b_j, then its mate a_i, at their midpoint) or
// a lone node, so that a path a -> b_j -> mate -> ... is relaxed in one sweep whichever lies left.
std::vector<std::uint32_t> sweep_order(const FlowState& flow) {
  std::vector<std::pair<double, std::uint32_t>> keyed;
  for (std::uint32_t i = 0; i < flow.n; ++i)
    if (flow.mate_a[i] < 0) keyed.push_back({flow.a[i].x, i});
  for (std::uint32_t j = 0; j < flow.m; ++j) {
    const std::int64_t i = flow.mate_b[j];
    keyed.push_back({i >= 0 ? (flow.a[i].x + flow.b[j].x) / 2 : flow.b[j].x, flow.node_of_b(j)});
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order;
  for (const auto& [x, v] : keyed) {
    order.push_back(v);
    if (flow.is_b(v) && flow.mate_b[flow.b_of_node(v)] >= 0)
      order.push_back(static_cast<std::uint32_t>(flow.mate_b[flow.b_of_node(v)]));
  }
  return order;
}

// Label-correcting over the residual arcs of the current flow on the candidate graph, potentials
// as labels: on return pi(v) <= pi(u) + c_uv on every such arc, which is what the searches need.
// From pi = 0 these are the shortest distances from a virtual root joined to every node at cost 0.
// Sweeps over the units, alternately forwards and backwards, each relaxing every node's arcs: on a
// line, shortest paths run mostly one way, so a few sweeps settle them. A flow that is not optimal
// on the candidates has a negative cycle: false once params.max_sweeps sweeps have not settled.
bool lower_potentials(FlowState& flow, const CandidateArcs& candidates, std::span<const std::uint32_t> order,
                      const DiagonalFlowParams& params) {
  auto& pi = flow.pi;
  bool changed = true;
  // Improvements within rounding are ignored (params.sweep_tolerance): rounding in pi(u) + c is
  // relative to the terms (both labels and the arc's cost), as in the certificate's check, whose
  // tolerance is larger, so that an arc the sweeps leave is never one the check flags.
  const auto relax_to = [&](std::uint32_t v, double from, double c) {
    const double d = from + c;
    if (!(d < pi[v] - params.sweep_tolerance * (std::fabs(from) + std::fabs(c) + std::fabs(pi[v])))) return;
    pi[v] = d;
    changed = true;
  };
  const auto relax_out = [&](std::uint32_t u) {
    const double d = pi[u];
    if (flow.is_a(u)) {
      for (const std::uint32_t j : candidates.row(u)) {
        if (flow.mate_a[u] == static_cast<std::int64_t>(j)) continue;
        const double c = flow.cost(u, j);
        if (c < flow.da[u] + flow.db[j]) relax_to(flow.node_of_b(j), d, c);
      }
      if (flow.mate_a[u] != kDiagonal) relax_to(flow.hb, d, flow.da[u]);
    } else if (flow.is_b(u)) {
      const std::int64_t mate = flow.mate_b[flow.b_of_node(u)];
      if (mate >= 0) relax_to(static_cast<std::uint32_t>(mate), d, -flow.mate_cost_a[mate]);
      if (mate == kDiagonal) relax_to(flow.ha, d, -flow.db[flow.b_of_node(u)]);
    } else if (u == flow.ha) {
      relax_to(flow.hb, d, 0);
      for (std::uint32_t j = 0; j < flow.m; ++j)
        if (flow.mate_b[j] != kDiagonal) relax_to(flow.node_of_b(j), d, flow.db[j]);
    } else {
      if (flow.flow_hub > 0) relax_to(flow.ha, d, 0);
      for (std::uint32_t i = 0; i < flow.n; ++i)
        if (flow.mate_a[i] == kDiagonal) relax_to(i, d, -flow.da[i]);
    }
  };
  for (std::size_t sweep = 0; changed; ++sweep) {
    check_work_deadline_now();
    if (sweep == params.max_sweeps) return false;
    changed = false;
    if (sweep % 2 == 0) {
      for (const std::uint32_t v : order) relax_out(v);
    } else {  // units backwards, each still b_j before its mate
      for (std::size_t k = order.size(); k-- > 0;) {
        const std::uint32_t v = order[k];
        if (flow.is_a(v) && flow.mate_a[v] >= 0) {
          relax_out(order[--k]);  // its mate b, just before it
          relax_out(v);
        } else {
          relax_out(v);
        }
      }
    }
    relax_out(flow.ha), relax_out(flow.hb), relax_out(flow.ha);
  }
  return true;
}

// Rows with a violated arc in the last check.
std::size_t violating_rows(const DualCertificate& certificate) {
  const auto v = certificate.violations();
  return static_cast<std::size_t>(
      std::count_if(v.begin(), v.end(), [](const DualCertificate::Violation& x) { return x.amount > 0; }));
}

// Checks every pair; while arcs are violated, adds them to the candidates and lowers again. When
// the lowering has stalled on a few rows (no fewer violated arcs than the round before, at most
// params.few_rows rows: sweeps that ignore improvements within rounding can leave such a row
// violated round after round), those rows are repaired instead (their potentials raised to
// feasible, the rows and their partners freed for the searches): every pair arc is then feasible,
// as after a certified round. false: no certificate within params.line_rounds rounds, or a
// negative cycle.
bool lower_until_certified(FlowState& flow, PairOracle& oracle, CandidateArcs& candidates, DualCertificate& certificate,
                           std::span<const std::uint32_t> order, const DiagonalFlowParams& params, HubArcs& hubs) {
  std::size_t before = 0;
  for (std::size_t round = 0;; ++round) {
    oracle.recompute_all();
    certificate.check_pairs(flow, oracle, params.line_top_arcs);
    const std::size_t violated = certificate.violations().size();
    if (violated == 0) return true;
    if (round > 0 && violated >= before && violating_rows(certificate) <= params.few_rows) {
      certificate.repair(flow, hubs);
      return true;
    }
    if (round == params.line_rounds) return false;
    before = violated;
    candidates.add(certificate.violated_arcs());
    certificate.clear_violations();
    if (!lower_potentials(flow, candidates, order, params)) return false;
  }
}

}  // namespace

bool line_start(const LineAlignment& alignment, const DiagonalFlowParams& params, FlowState& flow, HubArcs& hubs,
                PairOracle& oracle, CandidateArcs& candidates, DualCertificate& certificate) {
  for (const LineAlignment::Move move : alignment.moves) {
    if (move.step == LineAlignment::Step::pair) {
      const std::uint32_t i = alignment.order_a[move.rank_a], j = alignment.order_b[move.rank_b];
      const double c = flow.cost(i, j);
      if (c < flow.da[i] + flow.db[j]) {
        flow.mate_a[i] = j, flow.mate_b[j] = i, flow.mate_cost_a[i] = c, ++flow.flow_hub;
        continue;
      }
      flow.mate_a[i] = kDiagonal, ++flow.a_to_diagonal;
      flow.mate_b[j] = kDiagonal, ++flow.b_from_diagonal;
    } else if (move.step == LineAlignment::Step::delete_a) {
      flow.mate_a[alignment.order_a[move.rank_a]] = kDiagonal, ++flow.a_to_diagonal;
    } else {
      flow.mate_b[alignment.order_b[move.rank_b]] = kDiagonal, ++flow.b_from_diagonal;
    }
  }
  // Each pair routes one unit of the diagonal's supply straight to its demand (HA -> HB). That
  // flow is optimal for the line's points alone (the off-line points are free: they close no
  // cycle), so its residual graph has no negative cycle, and distances in it are potentials that
  // certify it.
  const std::vector<std::uint32_t> order = sweep_order(flow);
  if (lower_potentials(flow, candidates, order, params) &&
      lower_until_certified(flow, oracle, candidates, certificate, order, params, hubs)) {
    hubs.refresh_points(flow);
    return true;
  }
  // The empty flow with zero potentials: every reduced cost is a cost, >= 0, so no pair arc is
  // violated and the failed start's penalty must not linger in the dual bound.
  flow.clear();
  certificate.clear_violations();
  certificate.pairs_feasible();
  hubs.refresh_points(flow);
  return false;
}

}  // namespace fnet
