// What the solver asks about the pair arcs without listing them: the 2-d tree over B with, per
// box, the max of the potentials of its points, which bounds the reduced cost of every arc from a
// row into the box; the cheapest arcs of a row found with it; and the tree over A for the searches
// from B's side (the row reduction's column step, nearest neighbours).
// Invariant: the box maxima are upper bounds of the potentials of B in the box (potentials only
// fall between refreshes: after a search, update_maxima on its settled points of B; after a
// stage that moves potentials freely, recompute_all).
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "common/distance/flow_state.hpp"
#include "common/distance/infinity.hpp"
#include "common/distance/linf_kdtree.hpp"

namespace fnet {

class PairOracle {
 public:
  explicit PairOracle(const FlowState& flow);

  const LinfKdTree& tree_a() const { return tree_a_; }
  const LinfKdTree& tree_b() const { return tree_b_; }
  std::int32_t parent(std::int32_t box) const { return box_parent_[box]; }  // -1 at the root
  std::int32_t leaf_of_b(std::uint32_t j) const { return leaf_of_b_[j]; }
  // The leaf of the tree over B nearest a_i (by box distance, from the root down), found once.
  std::int32_t home_leaf(std::uint32_t i);

  // A lower bound on c_ij - pi(b_j) over the pair arcs from a_i into the box (+inf: none beats
  // the diagonal); the searches' box keys and the certificate's pruning both use it.
  double price_bound(std::uint32_t i, std::int32_t box) const {
    const auto& node = tree_b_.nodes()[box];
    const double c = flow_.power(tree_b_.box_distance(node, flow_.a[i]));
    if (!(c < flow_.da[i] + box_db_[box])) return kInf;  // no arc into the box beats the diagonal
    const BoxMax& m = box_max_[box];
    double bound = c - m.pi;
    if (flow_.power.is_identity()) {
      // c_ij >= |x_i - x_j| and >= |y_i - y_j|: bounds that follow potentials sloping across the box.
      const PlanePoint a = flow_.a[i];
      bound = std::max({bound, -a.x - m.minus_x, a.x - m.plus_x, -a.y - m.minus_y, a.y - m.plus_y});
    }
    return bound;
  }

  // Into top, ascending: the count smallest c_ij - pi(b_j) below limit over row i's pair arcs,
  // with their columns.
  void cheapest_prices(std::uint32_t i, std::size_t count, double limit,
                       std::vector<std::pair<double, std::uint32_t>>& top);

  void recompute_all();
  // After pi(b_j) changed: the maxima on the way from b_j's leaf up, while they change.
  void update_maxima(std::uint32_t j);

 private:
  static constexpr double kHuge = 1e300;
  struct BoxMax {  // over the box's points b: max pi(b), max pi(b) -+ x_b, max pi(b) -+ y_b
    double pi = -kHuge, minus_x = -kHuge, plus_x = -kHuge, minus_y = -kHuge, plus_y = -kHuge;
  };
  bool recompute_box(std::int32_t k);  // true when the box's maxima changed

  const FlowState& flow_;
  LinfKdTree tree_b_, tree_a_;
  std::vector<BoxMax> box_max_;
  std::vector<double> box_db_;  // max db over the box
  std::vector<std::int32_t> box_parent_, leaf_of_b_, home_leaf_;
  std::vector<std::int32_t> stack_;
};

}  // namespace fnet
