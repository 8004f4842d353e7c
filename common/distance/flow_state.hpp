// The flow network of the Wasserstein matching with the diagonal as two hubs, and the flow on it:
//   a_i -> b_j   cost c_ij, a_i -> HB cost da_i (a_i to the diagonal),
//   HA  -> b_j   cost db_j (b_j from the diagonal),  HA -> HB cost 0, unbounded.
// Supplies: a_i 1, HA m; demands: b_j 1, HB n. Pair arcs are those with c_ij < da_i + db_j (the
// others never beat sending both to the diagonal); they are never stored.
// Nodes: a_0..a_{n-1}, then b_0..b_{m-1}, then the hubs HA and HB.
// Invariants: mate_a[i] == j >= 0 exactly when mate_b[j] == i, with mate_cost_a[i] == c_ij;
// a_to_diagonal counts the i with mate_a[i] == kDiagonal, b_from_diagonal the j with mate_b[j] ==
// kDiagonal, flow_hub the units on HA -> HB. The reduced cost of u -> v is cost + pi(u) - pi(v).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/distance/arc_power.hpp"
#include "common/distance/linf_kdtree.hpp"

namespace fnet {

struct FlowState {
  static constexpr std::int64_t kNone = -1, kDiagonal = -2;

  // Arc costs power(length): a_i -> b_j power(||a_i - b_j||_inf), a_i -> HB and HA -> b_j the
  // power of the point's distance to the diagonal, |x - y| / 2. The flow empty, potentials 0.
  FlowState(std::span<const PlanePoint> a, std::span<const PlanePoint> b, ArcPower power);

  bool is_a(std::uint32_t v) const { return v < n; }
  bool is_b(std::uint32_t v) const { return v >= n && v < n + m; }
  std::uint32_t node_of_b(std::uint32_t j) const { return n + j; }
  std::uint32_t b_of_node(std::uint32_t v) const { return v - n; }
  std::size_t nodes() const { return n + m + 2; }

  double cost(std::uint32_t i, std::uint32_t j) const { return power(linf_distance(a[i], b[j])); }
  // A node that can take one more unit: a free b_j, or HB while it takes fewer than n.
  bool is_sink(std::uint32_t v) const {
    if (is_b(v)) return mate_b[b_of_node(v)] == kNone;
    if (v == hb) return a_to_diagonal + flow_hub < static_cast<std::int64_t>(n);
    return false;
  }
  // The diagonal's supply not yet routed: HA's units on neither HA -> b_j nor HA -> HB.
  std::int64_t diagonal_supply_left() const { return static_cast<std::int64_t>(m) - b_from_diagonal - flow_hub; }

  // The flow's cost: matched pairs plus every other point on the diagonal (free ones included).
  double primal_cost() const;
  // Pushes a unit along path (nodes, source first), cost_into[v] the cost of the path's arc into
  // v; a path HA -> HB alone carries as many units as both hubs can still exchange.
  void augment(std::span<const std::uint32_t> path, std::span<const double> cost_into);
  // No flow, potentials 0.
  void clear();

  std::uint32_t n, m, ha, hb;
  ArcPower power;
  std::vector<PlanePoint> a, b;
  std::vector<double> da, db;  // costs to the diagonal

  std::vector<std::int64_t> mate_a, mate_b;  // partner index, kDiagonal or kNone
  std::vector<double> mate_cost_a;
  std::int64_t flow_hub = 0, b_from_diagonal = 0, a_to_diagonal = 0;
  std::vector<double> pi;  // potentials: a_0..a_{n-1}, b_0..b_{m-1}, HA, HB
};

}  // namespace fnet
