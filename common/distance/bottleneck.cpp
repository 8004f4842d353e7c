#include "common/distance/bottleneck.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "common/distance/infinity.hpp"
#include "common/distance/linf_kdtree.hpp"
#include "common/distance/repeated_points.hpp"
#include "common/distance/work_deadline.hpp"

namespace fnet {

namespace {

double diagonal_distance(PlanePoint p) { return std::fabs(p.x - p.y) / 2; }

struct Side {
  std::vector<PlanePoint> points;
  std::vector<double> diagonal;
  std::vector<std::int64_t> mate;               // index on the other side, -1 if unmatched
  std::vector<std::uint32_t> by_birth;          // point indices, largest birth first
  std::vector<std::uint32_t> parent;            // local search: the point of the other side that reached it
  std::vector<std::uint32_t> by_coordinate[2];  // point indices by ascending x, by ascending y
  LinfKdTree tree;
  // The points farther than forced_r from the diagonal (ascending indices) and their own tree.
  std::vector<std::uint32_t> forced;
  std::optional<LinfKdTree> forced_tree;
  double forced_r = std::numeric_limits<double>::quiet_NaN();

  explicit Side(std::vector<PlanePoint> pts) : points(std::move(pts)), tree(points) {
    for (const PlanePoint p : points) diagonal.push_back(diagonal_distance(p));
    mate.assign(points.size(), -1);
    parent.assign(points.size(), 0);
    by_birth.resize(points.size());
    std::iota(by_birth.begin(), by_birth.end(), 0u);
    std::stable_sort(by_birth.begin(), by_birth.end(),
                     [&](std::uint32_t p, std::uint32_t q) { return points[p].x > points[q].x; });
  }

  // by_coordinate, sorted on first use (only listings need it).
  void sort_by_coordinate() {
    if (!by_coordinate[0].empty() || points.empty()) return;
    by_coordinate[0].assign(by_birth.rbegin(), by_birth.rend());
    by_coordinate[1] = by_coordinate[0];
    std::stable_sort(by_coordinate[1].begin(), by_coordinate[1].end(),
                     [&](std::uint32_t p, std::uint32_t q) { return points[p].y < points[q].y; });
  }
};

// One matching between the two diagrams, reused from one threshold to the next.
class ThresholdMatcher {
 public:
  ThresholdMatcher(std::vector<PlanePoint> a, std::vector<PlanePoint> b) : a_(std::move(a)), b_(std::move(b)) {
    // The line: the most common death, if at least a tenth of the points share it.
    std::vector<double> deaths;
    for (const Side* s : {&a_, &b_})
      for (const PlanePoint p : s->points) deaths.push_back(p.y);
    std::sort(deaths.begin(), deaths.end());
    std::size_t most = 0;
    for (std::size_t k = 0, run; k < deaths.size(); k += run) {
      run =
          static_cast<std::size_t>(std::upper_bound(deaths.begin() + k, deaths.end(), deaths[k]) - deaths.begin()) - k;
      if (run > most) most = run, line_y_ = deaths[k];
    }
    has_line_ = 10 * most >= deaths.size() && most > 1;
    root_label_.assign(std::max(a_.points.size(), b_.points.size()), 0);
  }

  // Every point goes to the diagonal or to a point of the other side: the largest of
  // min(diagonal distance, nearest distance) is a lower bound (and a candidate value).
  double nearest_lower_bound() const {
    double lower = 0;
    for (const Side* s : {&a_, &b_}) {
      const Side& o = (s == &a_) ? b_ : a_;
      for (const std::uint32_t i : s->tree.order())  // neighbours in turn: warm caches
        if (s->diagonal[i] > lower)
          lower = std::max(lower, o.tree.nearest_distance(s->points[i], s->diagonal[i], lower));
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
    bool broke = false;
    for (std::size_t i = 0; i < a_.points.size(); ++i) {
      const std::int64_t j = a_.mate[i];
      if (j >= 0 && linf_distance(a_.points[i], b_.points[j]) > r) a_.mate[i] = b_.mate[j] = -1, broke = true;
    }
    // From the matching of the last threshold, with a budget of visits when some of its pairs
    // broke: near the answer this is cheap, but the remains of a matching built for a threshold
    // far above can need many long augmenting paths, and then the sweep from nothing is the
    // better start.
    budget_ = broke ? 2 * (a_.points.size() + b_.points.size()) + 1024 : std::numeric_limits<std::size_t>::max();
    Cover c = cover_both(r);
    if (c != Cover::out_of_budget) return c == Cover::covered;
    std::fill(a_.mate.begin(), a_.mate.end(), -1);
    std::fill(b_.mate.begin(), b_.mate.end(), -1);
    budget_ = std::numeric_limits<std::size_t>::max();
    return cover_both(r) == Cover::covered;
  }

  // The distinct candidate values (pair distances, diagonal distances) strictly between lo and
  // hi, ascending, into `out`; or false, when more than `limit` turn up, with `estimate` the
  // count of all of them (extrapolated: from the pairs the sweep below would look at).
  bool list_candidates(double lo, double hi, std::size_t limit, std::vector<double>& out, double& estimate) {
    out.clear();
    a_.sort_by_coordinate();
    b_.sort_by_coordinate();
    for (const Side* s : {&a_, &b_})
      for (const double d : s->diagonal)
        if (d > lo && d < hi) out.push_back(d);
    // A pair's distance is its larger coordinate difference: lies in (lo, hi) exactly when |dx|
    // does and |dy| <= |dx|, or |dy| does and |dx| < |dy|. With both sides sorted by each
    // coordinate, the points of B whose difference to a lies in (lo, hi) form two runs (left and
    // right of a) whose ends only move forward as a moves forward: a sweep per coordinate finds
    // them, so the cost is the pairs in those runs, not a range search per point. Differences
    // are compared as computed (rounding is monotone), so the runs hold exactly those pairs.
    // The runs also hold the pairs whose other difference is the larger: allowed up to 8 per
    // candidate before the listing gives up.
    constexpr std::size_t kRunsPerCandidate = 8;
    std::size_t in_runs = 0;
    for (const Axis axis : {Axis::x, Axis::y})
      sweep_runs(axis, lo, hi,
                 [&](std::uint32_t, std::uint32_t first, std::uint32_t last) { in_runs += last - first; });
    if (in_runs > kRunsPerCandidate * limit) {
      estimate = static_cast<double>(in_runs) / kRunsPerCandidate;
      return false;
    }
    for (const Axis axis : {Axis::x, Axis::y}) {
      const std::vector<std::uint32_t>& b_order = b_.by_coordinate[static_cast<int>(axis)];
      sweep_runs(axis, lo, hi, [&](std::uint32_t i, std::uint32_t first, std::uint32_t last) {
        const PlanePoint p = a_.points[i];
        for (std::uint32_t k = first; k < last; ++k) {
          const PlanePoint q = b_.points[b_order[k]];
          const double dx = std::fabs(p.x - q.x), dy = std::fabs(p.y - q.y);
          if (axis == Axis::x ? dy <= dx : dx < dy) out.push_back(linf_distance(p, q));
        }
      });
    }
    if (out.size() > limit) {
      estimate = static_cast<double>(out.size());
      return false;
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
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
  enum class Axis { x, y };
  static double coordinate(PlanePoint p, Axis axis) { return axis == Axis::x ? p.x : p.y; }

  // For each point a_i of A (in ascending order of the coordinate), run(i, first, last) twice:
  // with the positions in B's order by that coordinate of the points b whose difference
  // |a_i - b| in it lies in (lo, hi), those below a_i and those above.
  template <class Run>
  void sweep_runs(Axis axis, double lo, double hi, Run run) const {
    const std::vector<std::uint32_t>& a_order = a_.by_coordinate[static_cast<int>(axis)];
    const std::vector<std::uint32_t>& b_order = b_.by_coordinate[static_cast<int>(axis)];
    const auto size = static_cast<std::uint32_t>(b_order.size());
    const auto at = [&](std::uint32_t k) { return coordinate(b_.points[b_order[k]], axis); };
    // below: [below_first, below_last) have a - b in (lo, hi); above: b - a in (lo, hi).
    std::uint32_t below_first = 0, below_last = 0, above_first = 0, above_last = 0;
    for (const std::uint32_t i : a_order) {
      const double c = coordinate(a_.points[i], axis);
      while (below_first < size && c - at(below_first) >= hi) ++below_first;
      while (below_last < size && c - at(below_last) > lo) ++below_last;
      while (above_first < size && at(above_first) - c <= lo) ++above_first;
      while (above_last < size && at(above_last) - c < hi) ++above_last;
      if (below_first < below_last) run(i, below_first, below_last);
      if (above_first < above_last) run(i, above_first, above_last);
    }
  }

  // Unmatched forced points of s take unmatched points of o within r, in two sweeps by
  // decreasing birth. First, on the line where most points lie (PD1 under floor: death = 0),
  // each takes the point of the line of largest birth: on a line this is a maximum matching in
  // sorted order that leaves the points nearest the diagonal out, also when one diagram has
  // more points than the other and the whole matching must shift. Then every point left takes
  // its nearest. With the matched points hidden from the tree this is cheap, and it spares most
  // of the searches below.
  void greedy(Side& s, Side& o, double r) {
    o.tree.restore_all();
    for (std::size_t j = 0; j < o.points.size(); ++j)
      if (o.mate[j] >= 0) o.tree.erase(static_cast<std::uint32_t>(j));
    for (const bool line : {true, false}) {
      if (line && !has_line_) continue;
      for (const std::uint32_t i : s.by_birth) {
        if (s.mate[i] >= 0 || s.diagonal[i] <= r || (line && s.points[i].y != line_y_)) continue;
        const std::int64_t v =
            line ? o.tree.take_rightmost_within(s.points[i], r, true) : o.tree.take_nearest_within(s.points[i], r);
        if (v >= 0) s.mate[i] = v, o.mate[v] = static_cast<std::int64_t>(i);
      }
    }
  }

  // Covering every forced point of s: bounded single-root searches, then Hopcroft-Karp phases on
  // the 2-d trees (Efrat-Itai-Katz, as in Hera), each phase labelled backwards from the ends (an
  // unmatched point of o, or one whose mate in s may go to the diagonal and is released) so that
  // roots at every distance augment along vertex-disjoint shortest paths in one phase. A root no
  // end reaches proves the threshold infeasible. out_of_budget: the visits allowed ran out.
  enum class Cover { covered, infeasible, out_of_budget };

  Cover cover_both(double r) {
    // A matching that covers the forced points of A and one that covers those of B give one that
    // covers both (Mendelsohn-Dulmage); the augmentations below never uncover a forced point.
    greedy(a_, b_, r);
    greedy(b_, a_, r);
    const Cover c = cover_forced(a_, b_, r);
    return c == Cover::covered ? cover_forced(b_, a_, r) : c;
  }

  Cover cover_forced(Side& s, Side& o, double r) {
    roots_.clear();
    for (const std::uint32_t i : s.by_birth)
      if (s.mate[i] < 0 && s.diagonal[i] > r) roots_.push_back(i);
    if (roots_.empty()) return Cover::covered;
    // First a bounded search from each root alone, the one that failed last first: near the
    // answer most augmenting paths are short and most failures local (a few points short of
    // partners), and one such search settles them where a phase would scan every layer.
    if (const auto w = std::find(roots_.begin(), roots_.end(), witness_); &s == witness_side_ && w != roots_.end())
      std::rotate(roots_.begin(), w, w + 1);
    std::size_t spent = 0;
    local_roots_ = roots_;
    for (const std::uint32_t root : local_roots_) {
      if (spent > o.points.size()) break;
      if (local_search(s, o, root, r, spent) == Local::no_path) {
        witness_side_ = &s;
        witness_ = root;
        return Cover::infeasible;
      }
    }
    if (!charge(spent)) return Cover::out_of_budget;
    for (;;) {
      const std::size_t unlabelled = label(s, o, r);
      if (unlabelled > 0) {
        witness_side_ = &s;
        return Cover::infeasible;
      }
      if (roots_.empty()) return Cover::covered;
      std::size_t visited = 0;
      for (const std::vector<std::uint32_t>& l : layers_) visited += l.size();
      if (!charge(visited)) return Cover::out_of_budget;
      std::size_t augmented = 0;
      for (const std::uint32_t root : roots_) augmented += find_path(s, o, root, r);
      if (augmented == 0) throw std::logic_error("bottleneck: a phase found no augmenting path in its layers");
    }
  }

  bool charge(std::size_t visits) {
    if (visits > budget_) return false;
    budget_ -= visits;
    return true;
  }

  enum class Local { augmented, no_path, gave_up };

  // Breadth-first alternating search from `root` alone, stopped at the first end (augmenting
  // along it) or after visiting kLocalBudget points of o (or four times the root's neighbours);
  // `spent` counts the visits.
  Local local_search(Side& s, Side& o, std::uint32_t root, double r, std::size_t& spent) {
    constexpr std::size_t kLocalBudget = 2048;
    o.tree.restore_all();
    frontier_.assign(1, root);
    std::size_t visited = 0, limit = kLocalBudget;
    for (std::size_t head = 0; head < frontier_.size(); ++head) {
      // Dense threshold graphs: the budget grows with the root's own neighbourhood.
      if (head == 1) limit = std::max(limit, 4 * visited);
      const std::uint32_t u = frontier_[head];
      for (std::int64_t v; (v = o.tree.take_within(s.points[u], r)) >= 0;) {
        check_work_deadline();
        ++spent;
        if (++visited > limit && head > 0) return Local::gave_up;
        o.parent[v] = u;
        const std::int64_t w = o.mate[v];
        if (w >= 0 && s.diagonal[w] > r) {
          frontier_.push_back(static_cast<std::uint32_t>(w));
          continue;
        }
        if (w >= 0) s.mate[w] = o.mate[v] = -1;
        for (std::int64_t x = v; x >= 0;) {
          const std::uint32_t y = o.parent[x];
          const std::int64_t next = s.mate[y];
          s.mate[y] = x;
          o.mate[x] = y;
          x = (y == root) ? -1 : next;
        }
        return Local::augmented;
      }
    }
    return Local::no_path;
  }

  // Labels every point of o with its distance to the nearest end (an unmatched point of o, or
  // one whose mate may go to the diagonal and be released): a breadth-first search backwards
  // from all ends at once, through the 2-d tree of s, until every unmatched forced point of s
  // (a root, listed in roots_ by increasing label) has a label. layers_[k] holds the points of o
  // labelled k, each layer with its 2-d tree. Returns how many roots no end reaches: each of
  // them proves the threshold infeasible (the witness_ is one).
  std::size_t label(Side& s, Side& o, double r) {
    std::size_t pending = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i) pending += s.mate[i] < 0 && s.diagonal[i] > r;
    roots_.clear();
    layers_.clear();
    if (pending == 0) return 0;
    // Points of s not forced (diagonal <= r) are never on a path. Where they are most of s, the
    // search runs on a tree of the forced ones alone, built once per threshold: in a dense
    // threshold graph it would otherwise take every one of them from the tree.
    LinfKdTree* tree = &s.tree;
    const std::vector<std::uint32_t>* point_of = nullptr;  // the forced tree's points in s
    std::size_t forced = 0;
    for (const double d : s.diagonal) forced += d > r;
    if (2 * forced < s.points.size()) {
      if (!(s.forced_r == r)) {
        s.forced.clear();
        std::vector<PlanePoint> points;
        for (std::uint32_t u = 0; u < s.points.size(); ++u)
          if (s.diagonal[u] > r) s.forced.push_back(u), points.push_back(s.points[u]);
        s.forced_tree.emplace(points);
        s.forced_r = r;
      }
      tree = &*s.forced_tree;
      point_of = &s.forced;
    }
    tree->restore_all();
    std::vector<std::uint32_t>& ends = layers_.emplace_back();
    for (std::size_t j = 0; j < o.points.size(); ++j)
      if (o.mate[j] < 0 || s.diagonal[o.mate[j]] <= r) ends.push_back(static_cast<std::uint32_t>(j));
    for (std::size_t k = 0; pending > 0 && !layers_[k].empty(); ++k) {
      next_.clear();
      for (const std::uint32_t v : layers_[k])
        for (std::int64_t t; (t = tree->take_within(o.points[v], r)) >= 0;) {
          check_work_deadline();
          const std::int64_t u = point_of ? (*point_of)[static_cast<std::size_t>(t)] : t;
          if (s.diagonal[u] <= r) continue;  // never needs a path, nor is on one
          const std::int64_t w = s.mate[u];
          if (w < 0) {
            roots_.push_back(static_cast<std::uint32_t>(u));
            root_label_[u] = static_cast<std::uint32_t>(k + 1);
            --pending;
          } else {
            next_.push_back(static_cast<std::uint32_t>(w));
          }
        }
      layers_.push_back(next_);
    }
    if (pending > 0) {
      // A root still in the tree: no end reached it.
      const auto reached = [&](std::uint32_t i) {
        if (!point_of) return !s.tree.is_present(i);
        const auto at = std::lower_bound(point_of->begin(), point_of->end(), i);
        return !tree->is_present(static_cast<std::uint32_t>(at - point_of->begin()));
      };
      for (std::uint32_t i = 0; i < s.points.size(); ++i)
        if (s.mate[i] < 0 && s.diagonal[i] > r && !reached(i)) {
          witness_ = i;
          break;
        }
      return pending;
    }
    std::size_t top = 0;
    for (const std::uint32_t root : roots_) top = std::max<std::size_t>(top, root_label_[root]);
    layers_.resize(top);
    layer_trees_.clear();
    for (const std::vector<std::uint32_t>& l : layers_) {
      layer_points_.clear();
      for (const std::uint32_t v : l) layer_points_.push_back(o.points[v]);
      layer_trees_.emplace_back(layer_points_);
    }
    return 0;
  }

  // Depth-first from `root` down the labels; on reaching an end, augments. Every point of o it
  // enters is deleted from its layer's tree, whether or not a path goes through it, so the paths
  // of one phase are vertex-disjoint and each is a shortest one for its root.
  bool find_path(Side& s, Side& o, std::uint32_t root, double r) {
    const std::size_t label = root_label_[root];
    path_s_.assign(1, root);
    path_o_.clear();
    while (!path_s_.empty()) {
      check_work_deadline();
      const std::size_t layer = label - 1 - path_o_.size();
      const std::int64_t local = layer_trees_[layer].take_within(s.points[path_s_.back()], r);
      if (local < 0) {  // a dead end: back up
        path_s_.pop_back();
        if (!path_o_.empty()) path_o_.pop_back();
        continue;
      }
      const std::uint32_t v = layers_[layer][static_cast<std::size_t>(local)];
      if (layer > 0) {
        path_s_.push_back(static_cast<std::uint32_t>(o.mate[v]));
        path_o_.push_back(v);
        continue;
      }
      if (const std::int64_t w = o.mate[v]; w >= 0) s.mate[w] = -1;
      path_o_.push_back(v);
      for (std::size_t k = 0; k < path_o_.size(); ++k) {
        s.mate[path_s_[k]] = path_o_[k];
        o.mate[path_o_[k]] = path_s_[k];
      }
      return true;
    }
    return false;
  }

  Side a_, b_;
  bool has_line_ = false;
  double line_y_ = 0;
  std::size_t budget_ = 0;  // visits left to the searches of this threshold
  const Side* witness_side_ = nullptr;
  std::uint32_t witness_ = 0;
  std::vector<std::uint32_t> root_label_;  // per point of the side being covered
  std::vector<std::uint32_t> local_roots_, roots_, frontier_, next_, path_s_, path_o_;
  std::vector<std::vector<std::uint32_t>> layers_;
  std::vector<PlanePoint> layer_points_;
  std::vector<LinfKdTree> layer_trees_;
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

  // Copies of points (ties everywhere): decided between the distinct points, exact.
  if (solve_distinct(va.points, vb.points)) {
    std::optional<MatchingBuilder> builder;
    if (matching) {
      builder.emplace(va, sa, a.size(), vb, sb, b.size());
      builder->essentials();
    }
    const DistinctBottleneck d =
        distinct_bottleneck(distinct_points(va.points), distinct_points(vb.points), builder ? &*builder : nullptr);
    result.value = result.lower = result.upper = std::max(d.value, essential);
    if (matching) *matching = builder->finish();
    return result;
  }

  // The matcher takes the points; a matching asked for needs them afterwards.
  ThresholdMatcher matcher(matching ? std::vector(va.points) : std::move(va.points),
                           matching ? std::vector(vb.points) : std::move(vb.points));
  double lo = matcher.nearest_lower_bound(), hi = matcher.all_to_diagonal();
  // The matching whose bottleneck is hi: all to the diagonal until a better one is found.
  std::vector<std::int64_t> best(matching ? va.points.size() : 0, -1);
  const auto found = [&](double r) {
    hi = matcher.value();
    if (hi > r) throw std::logic_error("bottleneck: a matching found at a threshold exceeds it");
    if (matching) best = matcher.mates_of_a();
  };
  const double rel = params.relative_error;
  auto done = [&] { return hi <= lo || (rel > 0 && hi <= (1 + rel) * lo) || hi <= essential; };
  if (!done()) {
    if (matcher.feasible(lo)) found(lo);
  }
  // Invariant: lo is infeasible (or lo == hi), hi is the bottleneck of a matching found. The
  // answer is a candidate value (an input distance) in (lo, hi]: once few enough lie strictly
  // between, they are listed and bisected by position; until then r is bisected over the bit
  // patterns of doubles (at most 64 tests, whatever the dynamic range). A feasible test snaps hi
  // down to the value of the matching it found.
  const std::size_t list_limit = 4 * (va.points.size() + vb.points.size()) + 64;
  std::vector<double> listed;
  bool have_list = false;
  // A failed listing costs a scan of its own: the next is tried once the bracket has narrowed
  // enough for the extrapolated count to fit.
  double estimate = 0, estimate_width = 1;
  while (!done()) {
    if (!have_list && estimate * (hi - lo) <= static_cast<double>(list_limit) * estimate_width) {
      have_list = matcher.list_candidates(lo, hi, list_limit, listed, estimate);
      estimate_width = hi - lo;
    }
    double mid;
    if (have_list) {
      const auto first = std::upper_bound(listed.begin(), listed.end(), lo);
      const auto last = std::lower_bound(first, listed.end(), hi);
      if (first == last) {  // no value between: nothing changes from lo to just below hi
        lo = hi;
        break;
      }
      mid = *(first + (last - first) / 2);
    } else {
      if (bits(hi) - bits(lo) <= 1) break;
      mid = std::bit_cast<double>(bits(lo) + (bits(hi) - bits(lo)) / 2);
    }
    if (matcher.feasible(mid))
      found(mid);
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
