#include "common/distance/flow_state.hpp"

#include <algorithm>
#include <cmath>

namespace fnet {

namespace {
std::vector<double> diagonal_costs(std::span<const PlanePoint> points, const ArcPower& power) {
  std::vector<double> out;
  out.reserve(points.size());
  for (const PlanePoint p : points) out.push_back(power(std::fabs(p.x - p.y) / 2));
  return out;
}
}  // namespace

FlowState::FlowState(std::span<const PlanePoint> a_points, std::span<const PlanePoint> b_points, ArcPower arc_power)
    : n(static_cast<std::uint32_t>(a_points.size())),
      m(static_cast<std::uint32_t>(b_points.size())),
      ha(n + m),
      hb(n + m + 1),
      power(arc_power),
      a(a_points.begin(), a_points.end()),
      b(b_points.begin(), b_points.end()),
      da(diagonal_costs(a_points, power)),
      db(diagonal_costs(b_points, power)),
      mate_a(n, kNone),
      mate_b(m, kNone),
      mate_cost_a(n, 0),
      pi(n + m + 2, 0.0) {}

double FlowState::primal_cost() const {
  double cost = 0;
  for (std::uint32_t i = 0; i < n; ++i) cost += mate_a[i] >= 0 ? mate_cost_a[i] : da[i];
  for (std::uint32_t j = 0; j < m; ++j)
    if (mate_b[j] < 0) cost += db[j];
  return cost;
}

void FlowState::augment(std::span<const std::uint32_t> path, std::span<const double> cost_into) {
  std::int64_t amount = 1;
  if (path.size() == 2 && path[0] == ha && path[1] == hb) {
    const std::int64_t supply = diagonal_supply_left();
    const std::int64_t demand = static_cast<std::int64_t>(n) - a_to_diagonal - flow_hub;
    amount = std::max<std::int64_t>(1, std::min(supply, demand));
  }
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const std::uint32_t u = path[k], v = path[k + 1];
    if (is_a(u) && is_b(v)) {  // a_u takes b_v
      mate_a[u] = b_of_node(v), mate_b[b_of_node(v)] = u, mate_cost_a[u] = cost_into[v];
    } else if (is_a(u) && v == hb) {  // a_u goes to the diagonal
      mate_a[u] = kDiagonal, ++a_to_diagonal;
    } else if (u == ha && is_b(v)) {  // b_v is fed by the diagonal
      mate_b[b_of_node(v)] = kDiagonal, ++b_from_diagonal;
    } else if (u == ha && v == hb) {
      flow_hub += amount;
    } else if (u == hb && v == ha) {
      --flow_hub;
    } else if (u == hb && is_a(v)) {  // a_v leaves the diagonal
      if (mate_a[v] == kDiagonal) mate_a[v] = kNone;
      --a_to_diagonal;
    } else if (v == ha) {  // b_u no longer fed by the diagonal
      if (mate_b[b_of_node(u)] == kDiagonal) mate_b[b_of_node(u)] = kNone;
      --b_from_diagonal;
    } else {  // b_u -> a_v: the pair (a_v, b_u) is undone
      if (mate_a[v] == static_cast<std::int64_t>(b_of_node(u))) mate_a[v] = kNone;
      if (mate_b[b_of_node(u)] == static_cast<std::int64_t>(v)) mate_b[b_of_node(u)] = kNone;
    }
  }
}

void FlowState::clear() {
  std::fill(mate_a.begin(), mate_a.end(), kNone);
  std::fill(mate_b.begin(), mate_b.end(), kNone);
  std::fill(mate_cost_a.begin(), mate_cost_a.end(), 0.0);
  std::fill(pi.begin(), pi.end(), 0.0);
  flow_hub = b_from_diagonal = a_to_diagonal = 0;
}

}  // namespace fnet
