#include "common/distance/pair_oracle.hpp"

namespace fnet {

PairOracle::PairOracle(const FlowState& flow) : flow_(flow), tree_b_(flow.b), tree_a_(flow.a) {
  const auto nodes = tree_b_.nodes();
  const auto order = tree_b_.order();
  box_parent_.assign(nodes.size(), -1);
  leaf_of_b_.assign(flow.m, -1);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (nodes[k].left >= 0) {
      box_parent_[nodes[k].left] = box_parent_[nodes[k].right] = static_cast<std::int32_t>(k);
    } else {
      for (std::uint32_t s = nodes[k].begin; s < nodes[k].end; ++s) leaf_of_b_[order[s]] = static_cast<std::int32_t>(k);
    }
  }
  box_max_.assign(nodes.size(), {});
  box_db_.assign(nodes.size(), 0.0);
  for (std::size_t k = nodes.size(); k-- > 0;) {
    if (nodes[k].left >= 0) {
      box_db_[k] = std::max(box_db_[nodes[k].left], box_db_[nodes[k].right]);
    } else {
      for (std::uint32_t s = nodes[k].begin; s < nodes[k].end; ++s)
        box_db_[k] = std::max(box_db_[k], flow.db[order[s]]);
    }
  }
  recompute_all();
}

std::int32_t PairOracle::home_leaf(std::uint32_t i) {
  if (home_leaf_.empty()) home_leaf_.assign(flow_.n, -1);
  if (home_leaf_[i] >= 0) return home_leaf_[i];
  const auto nodes = tree_b_.nodes();
  std::int32_t k = 0;
  while (nodes[k].left >= 0) {
    const auto& left = nodes[nodes[k].left];
    const auto& right = nodes[nodes[k].right];
    k = tree_b_.box_distance(left, flow_.a[i]) <= tree_b_.box_distance(right, flow_.a[i]) ? nodes[k].left
                                                                                          : nodes[k].right;
  }
  return home_leaf_[i] = k;
}

void PairOracle::cheapest_prices(std::uint32_t i, std::size_t count, double limit,
                                 std::vector<std::pair<double, std::uint32_t>>& top) {
  top.clear();
  const auto nodes = tree_b_.nodes();
  if (nodes.empty()) return;
  const auto order = tree_b_.order();
  const auto points = tree_b_.points();
  const PlanePoint a = flow_.a[i];
  const auto threshold = [&] { return top.size() < count ? limit : top.back().first; };
  stack_.assign(1, 0);
  while (!stack_.empty()) {
    const std::int32_t k = stack_.back();
    stack_.pop_back();
    const auto& box = nodes[k];
    if (!(price_bound(i, k) < threshold())) continue;
    if (box.left >= 0) {
      // Nearer child last: popped first, it lowers the threshold sooner.
      const double dl = tree_b_.box_distance(nodes[box.left], a), dr = tree_b_.box_distance(nodes[box.right], a);
      if (dl < dr) {
        stack_.push_back(box.right), stack_.push_back(box.left);
      } else {
        stack_.push_back(box.left), stack_.push_back(box.right);
      }
      continue;
    }
    for (std::uint32_t s = box.begin; s < box.end; ++s) {
      const std::uint32_t j = order[s];
      const double cj = flow_.power(linf_distance(a, points[j]));
      if (!(cj < flow_.da[i] + flow_.db[j])) continue;
      const double v = cj - flow_.pi[flow_.node_of_b(j)];
      if (!(v < threshold())) continue;
      if (top.size() == count) top.pop_back();
      top.insert(std::upper_bound(top.begin(), top.end(), std::make_pair(v, j)), {v, j});
    }
  }
}

void PairOracle::recompute_all() {
  for (std::size_t k = box_max_.size(); k-- > 0;) recompute_box(static_cast<std::int32_t>(k));
}

void PairOracle::update_maxima(std::uint32_t j) {
  for (std::int32_t k = leaf_of_b_[j]; k >= 0 && recompute_box(k); k = box_parent_[k]) {
  }
}

bool PairOracle::recompute_box(std::int32_t k) {
  const auto& node = tree_b_.nodes()[k];
  BoxMax value;
  if (node.left < 0) {
    const auto order = tree_b_.order();
    const auto points = tree_b_.points();
    for (std::uint32_t s = node.begin; s < node.end; ++s) {
      const std::uint32_t j = order[s];
      const double p = flow_.pi[flow_.node_of_b(j)];
      const PlanePoint b = points[j];
      value.pi = std::max(value.pi, p);
      value.minus_x = std::max(value.minus_x, p - b.x), value.plus_x = std::max(value.plus_x, p + b.x);
      value.minus_y = std::max(value.minus_y, p - b.y), value.plus_y = std::max(value.plus_y, p + b.y);
    }
  } else {
    const BoxMax& l = box_max_[node.left];
    const BoxMax& r = box_max_[node.right];
    value = {std::max(l.pi, r.pi), std::max(l.minus_x, r.minus_x), std::max(l.plus_x, r.plus_x),
             std::max(l.minus_y, r.minus_y), std::max(l.plus_y, r.plus_y)};
  }
  BoxMax& old = box_max_[k];
  const bool same = old.pi == value.pi && old.minus_x == value.minus_x && old.plus_x == value.plus_x &&
                    old.minus_y == value.minus_y && old.plus_y == value.plus_y;
  old = value;
  return !same;
}

}  // namespace fnet
