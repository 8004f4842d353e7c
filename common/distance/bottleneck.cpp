#include "common/distance/bottleneck.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "common/distance/linf_kdtree.hpp"

namespace fnet {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double diagonal_distance(PlanePoint p) { return std::fabs(p.x - p.y) / 2; }

struct Side {
  std::vector<PlanePoint> points;
  std::vector<double> diagonal;
  std::vector<std::int64_t> mate;     // index on the other side, -1 if unmatched
  std::vector<std::uint32_t> parent;  // search tree: the vertex of the other side that reached it
  LinfKdTree tree;

  explicit Side(std::vector<PlanePoint> pts) : points(std::move(pts)), tree(points) {
    for (const PlanePoint p : points) diagonal.push_back(diagonal_distance(p));
    mate.assign(points.size(), -1);
    parent.assign(points.size(), 0);
  }
};

// One matching between the two diagrams, reused from one threshold to the next.
class ThresholdMatcher {
 public:
  ThresholdMatcher(std::vector<PlanePoint> a, std::vector<PlanePoint> b) : a_(std::move(a)), b_(std::move(b)) {}

  double nearest_lower_bound() {
    double lower = 0;
    std::vector<std::uint32_t> nn;
    for (Side* s : {&a_, &b_}) {
      const Side& o = (s == &a_) ? b_ : a_;
      for (std::size_t i = 0; i < s->points.size(); ++i) {
        double best = s->diagonal[i];
        o.tree.nearest(s->points[i], 1, nn);
        if (!nn.empty()) best = std::min(best, linf_distance(s->points[i], o.points[nn[0]]));
        lower = std::max(lower, best);
      }
    }
    return lower;
  }

  double all_to_diagonal() const {
    double upper = 0;
    for (const Side* s : {&a_, &b_})
      for (const double d : s->diagonal) upper = std::max(upper, d);
    return upper;
  }

  // Is there a matching with every pair at distance <= r covering every point with diagonal > r?
  bool feasible(double r) {
    for (std::size_t i = 0; i < a_.points.size(); ++i) {
      const std::int64_t j = a_.mate[i];
      if (j >= 0 && linf_distance(a_.points[i], b_.points[j]) > r) a_.mate[i] = b_.mate[j] = -1;
    }
    // A matching that covers the forced points of A and one that covers those of B give one that
    // covers both (Mendelsohn-Dulmage); the augmentations below never uncover a forced point.
    greedy(a_, b_, r);
    greedy(b_, a_, r);
    for (std::size_t i = 0; i < a_.points.size(); ++i)
      if (a_.mate[i] < 0 && a_.diagonal[i] > r && !augment(a_, b_, static_cast<std::uint32_t>(i), r)) return false;
    for (std::size_t j = 0; j < b_.points.size(); ++j)
      if (b_.mate[j] < 0 && b_.diagonal[j] > r && !augment(b_, a_, static_cast<std::uint32_t>(j), r)) return false;
    return true;
  }

  // The bottleneck of the current matching, unmatched points going to the diagonal.
  double value() const {
    double v = 0;
    for (std::size_t i = 0; i < a_.points.size(); ++i)
      v = std::max(v, a_.mate[i] >= 0 ? linf_distance(a_.points[i], b_.points[a_.mate[i]]) : a_.diagonal[i]);
    for (std::size_t j = 0; j < b_.points.size(); ++j)
      if (b_.mate[j] < 0) v = std::max(v, b_.diagonal[j]);
    return v;
  }

  // The current matching: per point of A its mate in B, or -1 (the diagonal).
  const std::vector<std::int64_t>& mates_of_a() const { return a_.mate; }

 private:
  // Unmatched forced points of s take any unmatched point of o within r: with the matched points
  // hidden from the tree this is cheap, and it spares the searches below (thousands of duplicate
  // points would otherwise make each search walk the whole matched set).
  void greedy(Side& s, Side& o, double r) {
    o.tree.restore_all();
    for (std::size_t j = 0; j < o.points.size(); ++j)
      if (o.mate[j] >= 0) o.tree.erase(static_cast<std::uint32_t>(j));
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      if (s.mate[i] >= 0 || s.diagonal[i] <= r) continue;
      const std::int64_t v = o.tree.take_within(s.points[i], r);
      if (v >= 0) s.mate[i] = v, o.mate[v] = static_cast<std::int64_t>(i);
    }
  }

  // Breadth-first alternating search from the unmatched point `start` of s. It succeeds at an
  // unmatched point of o, or at a matched point of s that may go to the diagonal (it is released).
  bool augment(Side& s, Side& o, std::uint32_t start, double r) {
    o.tree.restore_all();
    queue_.clear();
    queue_.push_back(start);
    for (std::size_t head = 0; head < queue_.size(); ++head) {
      const std::uint32_t u = queue_[head];
      for (std::int64_t v; (v = o.tree.take_within(s.points[u], r)) >= 0;) {
        o.parent[v] = u;
        const std::int64_t w = o.mate[v];
        if (w >= 0 && s.diagonal[w] > r) {
          queue_.push_back(static_cast<std::uint32_t>(w));
          continue;
        }
        if (w >= 0) s.mate[w] = o.mate[v] = -1;
        for (std::int64_t x = v; x >= 0;) {
          const std::uint32_t y = o.parent[x];
          const std::int64_t next = s.mate[y];
          s.mate[y] = x;
          o.mate[x] = y;
          x = (y == start) ? -1 : next;
        }
        return true;
      }
    }
    return false;
  }

  Side a_, b_;
  std::vector<std::uint32_t> queue_;
};

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

}  // namespace

DistanceResult bottleneck_distance(const Diagram& a, const Diagram& b, const BottleneckParams& params,
                                   DiagramMatching* matching) {
  if (!(params.relative_error >= 0) || !std::isfinite(params.relative_error))
    throw std::invalid_argument("bottleneck: relative error must be finite and >= 0");
  if (matching) *matching = {};
  ViewSources sa, sb;
  ConventionView va = view_for(a, params.essential, matching ? &sa : nullptr),
                 vb = view_for(b, params.essential, matching ? &sb : nullptr);
  DistanceResult result;
  if (params.essential == EssentialConvention::separate) {
    if (std::string why = essential_count_mismatch(va, vb); !why.empty()) {
      result.value = result.lower = result.upper = kInf;
      result.infinite = true;
      result.reason = std::move(why);
      return result;
    }
  }
  double essential = 0;
  for (std::size_t k = 0; k < va.essential_births.size(); ++k)
    essential = std::max(essential, std::fabs(va.essential_births[k] - vb.essential_births[k]));

  // The matcher takes the points; a matching asked for needs them afterwards.
  ThresholdMatcher matcher(matching ? std::vector(va.points) : std::move(va.points),
                           matching ? std::vector(vb.points) : std::move(vb.points));
  double lo = matcher.nearest_lower_bound(), hi = matcher.all_to_diagonal();
  // The matching whose bottleneck is hi: all to the diagonal until a better one is found.
  std::vector<std::int64_t> best(matching ? va.points.size() : 0, -1);
  const auto found = [&] {
    hi = matcher.value();
    if (matching) best = matcher.mates_of_a();
  };
  const double rel = params.relative_error;
  auto done = [&] { return hi <= lo || (rel > 0 && hi <= (1 + rel) * lo) || hi <= essential; };
  if (!done()) {
    if (matcher.feasible(lo)) found();
  }
  // Invariant: lo is infeasible (or lo == hi), hi is the bottleneck of a matching found.
  while (!done() && bits(hi) - bits(lo) > 1) {
    const double mid = std::bit_cast<double>(bits(lo) + (bits(hi) - bits(lo)) / 2);
    if (matcher.feasible(mid))
      found();
    else
      lo = mid;
  }
  // Without relative error the loop ends with lo infeasible and its successor hi feasible.
  result.upper = std::max(hi, essential);
  result.lower = std::max(std::min(lo, hi), essential);
  result.exact = (rel == 0) || result.lower == result.upper;
  if (rel == 0) result.lower = result.upper;
  result.value = result.upper;
  if (matching) {
    MatchingBuilder builder(va, sa, a.size(), vb, sb, b.size());
    builder.essentials();
    std::vector<std::uint8_t> b_matched(vb.points.size(), 0);
    for (std::uint32_t i = 0; i < best.size(); ++i) {
      if (best[i] < 0) {
        builder.a_to_diagonal(i);
      } else {
        builder.pair(i, static_cast<std::uint32_t>(best[i]));
        b_matched[static_cast<std::size_t>(best[i])] = 1;
      }
    }
    for (std::uint32_t j = 0; j < vb.points.size(); ++j)
      if (!b_matched[j]) builder.b_to_diagonal(j);
    *matching = builder.finish();
  }
  return result;
}

}  // namespace fnet
