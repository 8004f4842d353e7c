// A static 2-d tree over diagram points for L-infinity queries: k nearest, "an unvisited point
// within r" with deletion (the matching searches of the bottleneck), and pruned traversals with
// per-node data (the optimality certificate of the Wasserstein solver). Built once per diagram.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "common/distance/essential_convention.hpp"

namespace fnet {

inline double linf_distance(PlanePoint a, PlanePoint b) {
  const double dx = a.x > b.x ? a.x - b.x : b.x - a.x;
  const double dy = a.y > b.y ? a.y - b.y : b.y - a.y;
  return dx > dy ? dx : dy;
}

class LinfKdTree {
 public:
  struct Node {
    double xmin, xmax, ymin, ymax;
    std::uint32_t begin, end;            // slice of order()
    std::int32_t left = -1, right = -1;  // children come after their parent in nodes()
  };

  explicit LinfKdTree(std::span<const PlanePoint> points);

  std::span<const Node> nodes() const { return nodes_; }
  std::span<const std::uint32_t> order() const { return order_; }  // point indices, leaf by leaf
  std::span<const PlanePoint> points() const { return points_; }

  // L-infinity distance from q to the node's bounding box (0 inside).
  double box_distance(const Node& node, PlanePoint q) const;

  // The k nearest points to q (fewer if the tree is smaller), nearest first. Ties are broken by a
  // hash of (salt, point), so that queries with different salts spread over duplicate points.
  void nearest(PlanePoint q, std::size_t k, std::vector<std::uint32_t>& out, std::uint64_t salt) const;
  void nearest(PlanePoint q, std::size_t k, std::vector<std::uint32_t>& out) const { nearest(q, k, out, 0); }

  // min(cap, the distance from q to its nearest point), erased points included; the search may
  // stop early at any value <= floor once one is found (then it returns that value).
  double nearest_distance(PlanePoint q, double cap, double floor) const;

  // Deletion layer: erase() hides a point from take_within(); restore_all() brings every erased point back.
  // take_within() returns an unerased point at distance <= r and erases it, or -1.
  std::int64_t take_within(PlanePoint q, double r);
  // The nearest unerased point at distance <= r (any of equals), erased; -1 if none.
  std::int64_t take_nearest_within(PlanePoint q, double r);
  // The unerased point at distance <= r with the largest x (any of equals), erased; -1 if none.
  // same_y: only among points with y == q.y.
  std::int64_t take_rightmost_within(PlanePoint q, double r, bool same_y = false);
  void erase(std::uint32_t point);
  void restore_all();
  bool is_present(std::uint32_t point) const { return !erased_[point]; }

 private:
  std::int32_t build(std::uint32_t begin, std::uint32_t end, std::int32_t parent, int depth);

  std::vector<PlanePoint> points_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;
  std::vector<std::int32_t> parent_;   // per node
  std::vector<std::uint32_t> alive_;   // per node: points not erased
  std::vector<std::int32_t> leaf_of_;  // per point
  std::vector<std::uint8_t> erased_;   // per point
  std::vector<std::uint32_t> erased_list_;
  std::vector<std::int32_t> stack_;
  mutable std::vector<std::int32_t> const_stack_;
  struct NearBest {  // nearest(): a point found, ordered by distance, then tie-break
    double d;
    std::uint64_t tie;
    std::uint32_t p;
    bool operator<(const NearBest& o) const { return d != o.d ? d < o.d : tie < o.tie; }
  };
  mutable std::vector<NearBest> near_best_;
  mutable std::vector<std::pair<double, std::int32_t>> near_stack_;  // (box distance, node)
};

}  // namespace fnet
