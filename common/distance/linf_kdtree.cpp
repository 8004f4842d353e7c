#include "common/distance/linf_kdtree.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace fnet {

namespace {
constexpr std::uint32_t kLeafSize = 8;
}

LinfKdTree::LinfKdTree(std::span<const PlanePoint> points)
    : points_(points.begin(), points.end()),
      order_(points.size()),
      leaf_of_(points.size(), -1),
      erased_(points.size(), 0) {
  for (std::uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  nodes_.reserve(2 * points.size() / kLeafSize + 2);
  if (!points.empty()) build(0, static_cast<std::uint32_t>(points.size()), -1, 0);
  alive_.resize(nodes_.size());
  for (std::size_t k = 0; k < nodes_.size(); ++k) alive_[k] = nodes_[k].end - nodes_[k].begin;
}

std::int32_t LinfKdTree::build(std::uint32_t begin, std::uint32_t end, std::int32_t parent, int depth) {
  const auto id = static_cast<std::int32_t>(nodes_.size());
  Node node{points_[order_[begin]].x,
            points_[order_[begin]].x,
            points_[order_[begin]].y,
            points_[order_[begin]].y,
            begin,
            end};
  for (std::uint32_t k = begin; k < end; ++k) {
    const PlanePoint p = points_[order_[k]];
    node.xmin = std::min(node.xmin, p.x), node.xmax = std::max(node.xmax, p.x);
    node.ymin = std::min(node.ymin, p.y), node.ymax = std::max(node.ymax, p.y);
  }
  nodes_.push_back(node);
  parent_.push_back(parent);
  if (end - begin <= kLeafSize) {
    for (std::uint32_t k = begin; k < end; ++k) leaf_of_[order_[k]] = id;
    return id;
  }
  // Split the wider side at the median; diagrams are often thin (PD1 under floor lies on y = 0).
  const bool by_x = (node.xmax - node.xmin) >= (node.ymax - node.ymin);
  (void)depth;
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](std::uint32_t a, std::uint32_t b) {
                     return by_x ? points_[a].x < points_[b].x : points_[a].y < points_[b].y;
                   });
  const std::int32_t left = build(begin, mid, id, depth + 1);
  const std::int32_t right = build(mid, end, id, depth + 1);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

double LinfKdTree::box_distance(const Node& node, PlanePoint q) const {
  const double dx = std::max({node.xmin - q.x, q.x - node.xmax, 0.0});
  const double dy = std::max({node.ymin - q.y, q.y - node.ymax, 0.0});
  return std::max(dx, dy);
}

namespace {
std::uint64_t mix(std::uint64_t x) {  // splitmix64 finalizer
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
}  // namespace

void LinfKdTree::nearest(PlanePoint q, std::size_t k, std::vector<std::uint32_t>& out, std::uint64_t salt) const {
  out.clear();
  if (nodes_.empty() || k == 0) return;
  // The best k so far as (distance, tie-break, point), ascending; depth first, nearer child first,
  // pruned by the k-th best. With a salt, boxes at exactly the worst distance are still opened:
  // they may win the tie-break. Scratch space is the tree's: a query allocates nothing.
  std::vector<NearBest>& best = near_best_;
  best.clear();
  const std::uint64_t seed = mix(salt);
  const auto worth_opening = [&](double d) {
    if (best.size() < k) return true;
    return d < best.back().d || (salt != 0 && d == best.back().d);
  };
  near_stack_.assign(1, {0.0, 0});
  while (!near_stack_.empty()) {
    const auto [dist, id] = near_stack_.back();
    near_stack_.pop_back();
    if (!worth_opening(dist)) continue;
    const Node& node = nodes_[id];
    if (node.left < 0) {
      for (std::uint32_t s = node.begin; s < node.end; ++s) {
        const std::uint32_t p = order_[s];
        const NearBest candidate{linf_distance(points_[p], q), salt == 0 ? p : mix(seed ^ p), p};
        if (best.size() == k) {
          if (!(candidate < best.back())) continue;
          best.pop_back();
        }
        best.insert(std::upper_bound(best.begin(), best.end(), candidate), candidate);
      }
      continue;
    }
    const double dl = box_distance(nodes_[node.left], q), dr = box_distance(nodes_[node.right], q);
    if (dl <= dr) {
      near_stack_.push_back({dr, node.right}), near_stack_.push_back({dl, node.left});
    } else {
      near_stack_.push_back({dl, node.left}), near_stack_.push_back({dr, node.right});
    }
  }
  for (const NearBest& b : best) out.push_back(b.p);
}

double LinfKdTree::nearest_distance(PlanePoint q, double cap, double floor) const {
  double best = cap;
  if (nodes_.empty()) return best;
  const_stack_.clear();
  const_stack_.push_back(0);
  while (!const_stack_.empty() && best > floor) {
    const Node& node = nodes_[const_stack_.back()];
    const_stack_.pop_back();
    if (box_distance(node, q) >= best) continue;
    if (node.left < 0) {
      for (std::uint32_t s = node.begin; s < node.end; ++s) best = std::min(best, linf_distance(points_[order_[s]], q));
      continue;
    }
    const double dl = box_distance(nodes_[node.left], q), dr = box_distance(nodes_[node.right], q);
    const_stack_.push_back(dl <= dr ? node.right : node.left);
    const_stack_.push_back(dl <= dr ? node.left : node.right);
  }
  return best;
}

std::int64_t LinfKdTree::take_within(PlanePoint q, double r) {
  if (nodes_.empty()) return -1;
  stack_.clear();
  stack_.push_back(0);
  while (!stack_.empty()) {
    const std::int32_t id = stack_.back();
    stack_.pop_back();
    const Node& node = nodes_[id];
    if (alive_[id] == 0 || box_distance(node, q) > r) continue;
    if (node.left < 0) {
      for (std::uint32_t s = node.begin; s < node.end; ++s) {
        const std::uint32_t p = order_[s];
        if (!erased_[p] && linf_distance(points_[p], q) <= r) {
          erase(p);
          return p;
        }
      }
      continue;
    }
    stack_.push_back(node.right);
    stack_.push_back(node.left);
  }
  return -1;
}

std::int64_t LinfKdTree::take_nearest_within(PlanePoint q, double r) {
  if (nodes_.empty()) return -1;
  // Depth first, nearer child first, pruned by the best so far.
  std::int64_t best = -1;
  double best_d = r;
  stack_.clear();
  stack_.push_back(0);
  while (!stack_.empty()) {
    const std::int32_t id = stack_.back();
    stack_.pop_back();
    const Node& node = nodes_[id];
    if (alive_[id] == 0 || box_distance(node, q) > best_d) continue;
    if (node.left < 0) {
      for (std::uint32_t s = node.begin; s < node.end; ++s) {
        const std::uint32_t p = order_[s];
        if (erased_[p]) continue;
        const double d = linf_distance(points_[p], q);
        if (d < best_d || (d == best_d && best < 0)) best_d = d, best = p;
      }
      continue;
    }
    const double dl = box_distance(nodes_[node.left], q), dr = box_distance(nodes_[node.right], q);
    stack_.push_back(dl <= dr ? node.right : node.left);
    stack_.push_back(dl <= dr ? node.left : node.right);
  }
  if (best >= 0) erase(static_cast<std::uint32_t>(best));
  return best;
}

std::int64_t LinfKdTree::take_rightmost_within(PlanePoint q, double r, bool same_y) {
  if (nodes_.empty()) return -1;
  std::int64_t best = -1;
  double best_x = 0;
  stack_.clear();
  stack_.push_back(0);
  while (!stack_.empty()) {
    const std::int32_t id = stack_.back();
    stack_.pop_back();
    const Node& node = nodes_[id];
    if (alive_[id] == 0 || box_distance(node, q) > r || (best >= 0 && node.xmax <= best_x)) continue;
    if (same_y && (q.y < node.ymin || q.y > node.ymax)) continue;
    if (node.left < 0) {
      for (std::uint32_t s = node.begin; s < node.end; ++s) {
        const std::uint32_t p = order_[s];
        if (erased_[p] || linf_distance(points_[p], q) > r || (same_y && points_[p].y != q.y)) continue;
        if (best < 0 || points_[p].x > best_x) best_x = points_[p].x, best = p;
      }
      continue;
    }
    const bool right_first = nodes_[node.right].xmax >= nodes_[node.left].xmax;
    stack_.push_back(right_first ? node.left : node.right);
    stack_.push_back(right_first ? node.right : node.left);
  }
  if (best >= 0) erase(static_cast<std::uint32_t>(best));
  return best;
}

void LinfKdTree::erase(std::uint32_t point) {
  if (erased_[point]) return;
  erased_[point] = 1;
  erased_list_.push_back(point);
  for (std::int32_t id = leaf_of_[point]; id >= 0; id = parent_[id]) --alive_[id];
}

void LinfKdTree::restore_all() {
  for (const std::uint32_t point : erased_list_) {
    erased_[point] = 0;
    for (std::int32_t id = leaf_of_[point]; id >= 0; id = parent_[id]) ++alive_[id];
  }
  erased_list_.clear();
}

}  // namespace fnet
