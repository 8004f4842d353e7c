#include "common/distance/greedy_start.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include "common/distance/infinity.hpp"

namespace fnet {

void greedy_start(FlowState& flow, HubArcs& hubs, PairOracle& oracle, std::size_t nearest) {
  constexpr std::int64_t kDiagonal = FlowState::kDiagonal, kNone = FlowState::kNone;
  // Row reduction: with pi(b) = pi(HA) = pi(HB) = 0, pi(a_i) = -(its cheapest way out) keeps every
  // reduced cost >= 0, and a_i's cheapest arc is tight: take it when its head is still free (the
  // diagonal always is).
  std::vector<std::uint32_t> near;
  for (std::uint32_t i = 0; i < flow.n; ++i) {
    oracle.tree_b().nearest(flow.a[i], nearest, near, i);
    double best = flow.da[i];
    std::int64_t to = kDiagonal;
    for (const std::uint32_t j : near) {
      const double c = flow.cost(i, j);
      if (c < best || (c == best && to >= 0 && flow.mate_b[to] != kNone && flow.mate_b[j] == kNone)) best = c, to = j;
    }
    flow.pi[i] = -best;
    if (to == kDiagonal) {
      flow.mate_a[i] = kDiagonal, ++flow.a_to_diagonal;
    } else if (flow.mate_b[to] == kNone) {
      flow.mate_a[i] = to, flow.mate_b[to] = i, flow.mate_cost_a[i] = best;
    }
    hubs.refresh(flow, i);
  }
  // Column step for the b_j still free: pi(b_j) = min(db_j, min_i c_ij + pi(a_i)) keeps every arc
  // into b_j feasible; when the diagonal attains it, b_j is fed from the diagonal (tight), so the
  // diagonal's supply is not left to be routed last, each unit by a search over most of the graph.
  const LinfKdTree& tree_a = oracle.tree_a();
  const auto nodes = tree_a.nodes();
  const auto order = tree_a.order();
  std::vector<double> min_pi(nodes.size(), kInf);
  for (std::size_t k = nodes.size(); k-- > 0;) {
    if (nodes[k].left >= 0) {
      min_pi[k] = std::min(min_pi[nodes[k].left], min_pi[nodes[k].right]);
    } else {
      for (std::uint32_t s = nodes[k].begin; s < nodes[k].end; ++s) min_pi[k] = std::min(min_pi[k], flow.pi[order[s]]);
    }
  }
  std::vector<std::int32_t> stack;
  for (std::uint32_t j = 0; j < flow.m; ++j) {
    if (flow.mate_b[j] != kNone || nodes.empty()) continue;
    double best = flow.db[j];
    stack.assign(1, 0);
    while (!stack.empty()) {
      const auto& node = nodes[stack.back()];
      stack.pop_back();
      const double c = flow.power(tree_a.box_distance(node, flow.b[j]));
      if (!(c + min_pi[&node - nodes.data()] < best)) continue;
      if (node.left >= 0) {
        stack.push_back(node.left), stack.push_back(node.right);
        continue;
      }
      for (std::uint32_t s = node.begin; s < node.end; ++s) {
        const std::uint32_t i = order[s];
        best = std::min(best, flow.cost(i, j) + flow.pi[i]);
      }
    }
    flow.pi[flow.node_of_b(j)] = best;
    if (best == flow.db[j]) flow.mate_b[j] = kDiagonal, ++flow.b_from_diagonal;
  }
  for (std::uint32_t j = 0; j < flow.m; ++j) hubs.refresh(flow, flow.node_of_b(j));
  oracle.recompute_all();
}

}  // namespace fnet
