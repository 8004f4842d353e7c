#include "common/distance/diagonal_flow.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "common/distance/sorted_birth_seed.hpp"

namespace fnet {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> diagonal_costs(std::span<const PlanePoint> points, const ArcPower& power) {
  std::vector<double> out;
  out.reserve(points.size());
  for (const PlanePoint p : points) out.push_back(power(std::fabs(p.x - p.y) / 2));
  return out;
}
}  // namespace

DiagonalFlow::DiagonalFlow(std::span<const PlanePoint> a, std::span<const PlanePoint> b, ArcPower power)
    : n_(static_cast<std::uint32_t>(a.size())),
      m_(static_cast<std::uint32_t>(b.size())),
      ha_(n_ + m_),
      hb_(n_ + m_ + 1),
      power_(power),
      da_(diagonal_costs(a, power_)),
      db_(diagonal_costs(b, power_)),
      mate_a_(n_, kNone),
      mate_b_(m_, kNone),
      mate_cost_a_(n_, 0),
      pi_(n_ + m_ + 2, 0.0),
      hub_a_(m_),
      hub_b_(n_),
      dist_(n_ + m_ + 2, kInf),
      pred_cost_(n_ + m_ + 2, 0),
      pred_(n_ + m_ + 2, 0),
      seen_(n_ + m_ + 2, 0),
      final_(n_ + m_ + 2, 0),
      heap_(n_ + m_ + 2) {
  for (std::uint32_t j = 0; j < m_; ++j) refresh(node_of_b(j));
  pa_.assign(a.begin(), a.end());
  tree_b_ = std::make_unique<LinfKdTree>(b);
  const auto nodes = tree_b_->nodes();
  const auto order = tree_b_->order();
  box_parent_.assign(nodes.size(), -1);
  leaf_of_b_.assign(b.size(), -1);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (nodes[k].left >= 0) {
      box_parent_[nodes[k].left] = box_parent_[nodes[k].right] = static_cast<std::int32_t>(k);
    } else {
      for (std::uint32_t s = nodes[k].begin; s < nodes[k].end; ++s) leaf_of_b_[order[s]] = static_cast<std::int32_t>(k);
    }
  }
  box_max_.assign(nodes.size(), {});
  box_run_.assign(nodes.size(), 0);
  box_db_.assign(nodes.size(), 0.0);
  for (std::size_t k = nodes.size(); k-- > 0;) {
    if (nodes[k].left >= 0) {
      box_db_[k] = std::max(box_db_[nodes[k].left], box_db_[nodes[k].right]);
    } else {
      for (std::uint32_t s = nodes[k].begin; s < nodes[k].end; ++s) box_db_[k] = std::max(box_db_[k], db_[order[s]]);
    }
  }
  box_done_.assign(nodes.size(), 0);
  for (std::size_t k = nodes.size(); k-- > 0;) recompute_box(static_cast<std::int32_t>(k));
  tree_a_ = std::make_unique<LinfKdTree>(pa_);
}

void DiagonalFlow::greedy_start() {
  started_ = true;
  // Row reduction: with pi(b) = pi(HA) = pi(HB) = 0, pi(a_i) = -(its cheapest way out) keeps every
  // reduced cost >= 0, and a_i's cheapest arc is tight: take it when its head is still free (the
  // diagonal always is). Consecutive frames' diagrams are close, so most rows are settled here.
  std::vector<std::uint32_t> near;
  for (std::uint32_t i = 0; i < n_; ++i) {
    tree_b_->nearest(pa_[i], 4, near, i);
    double best = da_[i];
    std::int64_t to = kDiagonal;
    for (const std::uint32_t j : near) {
      const double c = cost(i, j);
      if (c < best || (c == best && to >= 0 && mate_b_[to] != kNone && mate_b_[j] == kNone)) best = c, to = j;
    }
    pi_[i] = -best;
    if (to == kDiagonal) {
      mate_a_[i] = kDiagonal, ++a_to_diagonal_;
    } else if (mate_b_[to] == kNone) {
      mate_a_[i] = to, mate_b_[to] = i, mate_cost_a_[i] = best;
    }
    refresh(i);
  }
  // Column step for the b_j still free: pi(b_j) = min(db_j, min_i c_ij + pi(a_i)) keeps every arc
  // into b_j feasible; when the diagonal attains it, b_j is fed from the diagonal (tight). Without
  // this the diagonal's supply is routed last, each unit by a search over most of the graph.
  const LinfKdTree& tree_a = *tree_a_;
  const auto nodes = tree_a.nodes();
  const auto order = tree_a.order();
  std::vector<double> min_pi(nodes.size(), kInf);
  for (std::size_t k = nodes.size(); k-- > 0;) {
    if (nodes[k].left >= 0) {
      min_pi[k] = std::min(min_pi[nodes[k].left], min_pi[nodes[k].right]);
    } else {
      for (std::uint32_t s = nodes[k].begin; s < nodes[k].end; ++s) min_pi[k] = std::min(min_pi[k], pi_[order[s]]);
    }
  }
  std::vector<std::int32_t> stack;
  const auto points_b = tree_b_->points();
  for (std::uint32_t j = 0; j < m_; ++j) {
    if (mate_b_[j] != kNone || nodes.empty()) continue;
    double best = db_[j];
    stack.assign(1, 0);
    while (!stack.empty()) {
      const auto& node = nodes[stack.back()];
      stack.pop_back();
      const double c = power_(tree_a.box_distance(node, points_b[j]));
      if (!(c + min_pi[&node - nodes.data()] < best)) continue;
      if (node.left >= 0) {
        stack.push_back(node.left), stack.push_back(node.right);
        continue;
      }
      for (std::uint32_t s = node.begin; s < node.end; ++s) {
        const std::uint32_t i = order[s];
        best = std::min(best, cost(i, j) + pi_[i]);
      }
    }
    pi_[node_of_b(j)] = best;
    if (best == db_[j]) mate_b_[j] = kDiagonal, ++b_from_diagonal_;
  }
  for (std::uint32_t j = 0; j < m_; ++j) refresh(node_of_b(j));
  recompute_all_boxes();
}

void DiagonalFlow::reset_flow() {
  std::fill(mate_a_.begin(), mate_a_.end(), kNone);
  std::fill(mate_b_.begin(), mate_b_.end(), kNone);
  std::fill(mate_cost_a_.begin(), mate_cost_a_.end(), 0.0);
  std::fill(pi_.begin(), pi_.end(), 0.0);
  flow_hub_ = b_from_diagonal_ = a_to_diagonal_ = 0;
  for (std::uint32_t v = 0; v < n_ + m_; ++v) refresh(v);
}

bool DiagonalFlow::line_start(const LineAlignment& alignment) {
  // The programme's optimal matching of the line's points as the flow (a pair that costs more than
  // sending both to the diagonal sends both there), the off-line points left free. The flow is
  // empty here: nothing has started it.
  for (const LineAlignment::Move move : alignment.moves) {
    if (move.step == LineAlignment::Step::pair) {
      const std::uint32_t i = alignment.order_a[move.rank_a], j = alignment.order_b[move.rank_b];
      const double c = cost(i, j);
      if (c < da_[i] + db_[j]) {
        mate_a_[i] = j, mate_b_[j] = i, mate_cost_a_[i] = c, ++flow_hub_;
        continue;
      }
      mate_a_[i] = kDiagonal, ++a_to_diagonal_;
      mate_b_[j] = kDiagonal, ++b_from_diagonal_;
    } else if (move.step == LineAlignment::Step::delete_a) {
      mate_a_[alignment.order_a[move.rank_a]] = kDiagonal, ++a_to_diagonal_;
    } else {
      mate_b_[alignment.order_b[move.rank_b]] = kDiagonal, ++b_from_diagonal_;
    }
  }
  // Each pair routes one unit of the diagonal's supply straight to its demand (HA -> HB).
  // That flow is optimal for the line's points alone (the off-line points are free: they close no
  // cycle), so its residual graph has no negative cycle, and distances in it are potentials that
  // certify it: computed on the candidates, then checked over every pair; arcs found violated join
  // the candidates and the distances come down along them. A band that cut the programme's
  // optimum off shows as a negative cycle: the sweeps' limit ends the attempt.
  started_ = true;
  if (lower_potentials() && lower_until_certified()) {
    for (std::uint32_t v = 0; v < n_ + m_; ++v) refresh(v);
    on_line_ = true;
    return true;
  }
  reset_flow();
  started_ = false;
  return false;
}

bool DiagonalFlow::lower_until_certified() {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> extra;
  for (std::size_t round = 0;; ++round) {
    recompute_all_boxes();
    check_pairs(kLineTopArcs);
    ++rounds_;
    if (violations_.empty()) return true;
    if (round == kLineRounds) return false;
    extra.clear();
    for (const Violation& v : violations_) extra.push_back({v.row, v.column});
    add_candidates(extra);
    violations_.clear();
    if (!lower_potentials()) return false;
  }
}

bool DiagonalFlow::lower_potentials() {
  // Label-correcting over the residual arcs of the current flow on the candidate graph, potentials
  // as labels: on return pi(v) <= pi(u) + c_uv on every such arc, which is what the searches need.
  // From pi = 0 (the first call) these are the shortest distances from a virtual root joined to
  // every node at cost 0. Sweeps in birth order, alternately up and down, each relaxing every node's arcs: on a
  // line, shortest paths run mostly one way, so a few sweeps settle them. A flow that is not
  // optimal on the candidates has a negative cycle: the sweep limit ends the attempt.
  if (sweep_order_.empty()) {
    // Units in birth order: a matched pair (b_j, then its mate a_i, at their midpoint) or a lone
    // node, so that a path a -> b_j -> mate -> ... is relaxed in one sweep whichever lies left.
    const auto points_b = tree_b_->points();
    std::vector<std::pair<double, std::uint32_t>> keyed;
    for (std::uint32_t i = 0; i < n_; ++i)
      if (mate_a_[i] < 0) keyed.push_back({pa_[i].x, i});
    for (std::uint32_t j = 0; j < m_; ++j) {
      const std::int64_t i = mate_b_[j];
      keyed.push_back({i >= 0 ? (pa_[i].x + points_b[j].x) / 2 : points_b[j].x, node_of_b(j)});
    }
    std::sort(keyed.begin(), keyed.end());
    for (const auto& [x, v] : keyed) {
      sweep_order_.push_back(v);
      if (is_b(v) && mate_b_[b_of_node(v)] >= 0)
        sweep_order_.push_back(static_cast<std::uint32_t>(mate_b_[b_of_node(v)]));
    }
  }
  bool changed = true;
  // Improvements within rounding are ignored: on a line under q = 1 whole families of cycles cost
  // exactly 0, and their rounded sums would otherwise keep lowering the labels by an ulp forever.
  const auto relax_to = [&](std::uint32_t v, double d) {
    if (!(d < pi_[v] - 0x1p-50 * std::max(1.0, std::fabs(d)))) return;
    pi_[v] = d;
    changed = true;
  };
  const auto relax_out = [&](std::uint32_t u) {
    const double d = pi_[u];
    if (is_a(u)) {
      for (std::uint32_t k = cand_start_[u]; k < cand_start_[u + 1]; ++k) {
        const std::uint32_t j = cand_[k];
        if (mate_a_[u] == static_cast<std::int64_t>(j)) continue;
        const double c = cost(u, j);
        if (c < da_[u] + db_[j]) relax_to(node_of_b(j), d + c);
      }
      if (mate_a_[u] != kDiagonal) relax_to(hb_, d + da_[u]);
    } else if (is_b(u)) {
      const std::int64_t mate = mate_b_[b_of_node(u)];
      if (mate >= 0) relax_to(static_cast<std::uint32_t>(mate), d - mate_cost_a_[mate]);
      if (mate == kDiagonal) relax_to(ha_, d - db_[b_of_node(u)]);
    } else if (u == ha_) {
      relax_to(hb_, d);
      for (std::uint32_t j = 0; j < m_; ++j)
        if (mate_b_[j] != kDiagonal) relax_to(node_of_b(j), d + db_[j]);
    } else {
      if (flow_hub_ > 0) relax_to(ha_, d);
      for (std::uint32_t i = 0; i < n_; ++i)
        if (mate_a_[i] == kDiagonal) relax_to(i, d - da_[i]);
    }
  };
  for (std::size_t sweep = 0; changed; ++sweep) {
    if (sweep == kMaxSweeps) return false;
    changed = false;
    if (sweep % 2 == 0) {
      for (const std::uint32_t v : sweep_order_) relax_out(v);
    } else {  // units backwards, each still b_j before its mate
      for (std::size_t k = sweep_order_.size(); k-- > 0;) {
        const std::uint32_t v = sweep_order_[k];
        if (is_a(v) && mate_a_[v] >= 0) {
          relax_out(sweep_order_[--k]);  // its mate b, just before it
          relax_out(v);
        } else {
          relax_out(v);
        }
      }
    }
    relax_out(ha_), relax_out(hb_), relax_out(ha_);
  }
  return true;
}

void DiagonalFlow::recompute_all_boxes() {
  for (std::size_t k = box_max_.size(); k-- > 0;) recompute_box(static_cast<std::int32_t>(k));
}

bool DiagonalFlow::recompute_box(std::int32_t k) {
  const auto& node = tree_b_->nodes()[k];
  BoxMax value;
  if (node.left < 0) {
    const auto order = tree_b_->order();
    const auto points = tree_b_->points();
    for (std::uint32_t s = node.begin; s < node.end; ++s) {
      const std::uint32_t j = order[s];
      const double p = pi_[node_of_b(j)];
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

double DiagonalFlow::cost(std::uint32_t i, std::uint32_t j) const {
  return power_(linf_distance(pa_[i], tree_b_->points()[j]));
}

double DiagonalFlow::box_price_bound(std::uint32_t i, std::int32_t node) const {
  const auto& box = tree_b_->nodes()[node];
  const double c = power_(tree_b_->box_distance(box, pa_[i]));
  if (!(c < da_[i] + box_db_[node])) return kInf;  // no arc into the box beats the diagonal
  const BoxMax& m = box_max_[node];
  double bound = c - m.pi;
  if (power_.is_identity()) {
    // c_ij >= |x_i - x_j| and >= |y_i - y_j|: bounds that follow potentials sloping across the box.
    const PlanePoint a = pa_[i];
    bound = std::max({bound, -a.x - m.minus_x, a.x - m.plus_x, -a.y - m.minus_y, a.y - m.plus_y});
  }
  return bound;
}

double DiagonalFlow::box_key(std::uint32_t i, std::int32_t node) const {
  const auto& box = tree_b_->nodes()[node];
  if (box_run_[node] == run_ && box_done_[node] == box.end - box.begin) return kInf;  // all settled
  const double bound = box_price_bound(i, node);
  if (bound == kInf) return kInf;
  return dist_[i] + std::max(0.0, bound + pi_[i]);
}

void DiagonalFlow::open_box(std::uint32_t i, std::int32_t node) {
  // Boxes whose key is not above the current distance would pop next anyway: open them at once.
  const auto nodes = tree_b_->nodes();
  const auto order = tree_b_->order();
  const double d = dist_[i];
  box_stack_.clear();
  box_stack_.push_back(node);
  while (!box_stack_.empty()) {
    const std::int32_t k = box_stack_.back();
    box_stack_.pop_back();
    const auto& box = nodes[k];
    ++boxes_opened_;
    if (box.left >= 0) {
      for (const std::int32_t child : {box.left, box.right}) {
        const double key = box_key(i, child);
        if (key == kInf) continue;
        if (key <= current_) {
          box_stack_.push_back(child);
        } else {
          push_box(i, child, key);
        }
      }
      continue;
    }
    for (std::uint32_t s = box.begin; s < box.end; ++s) {
      const std::uint32_t j = order[s];
      if (mate_a_[i] == static_cast<std::int64_t>(j)) continue;
      const double c = cost(i, j);
      if (!(c < da_[i] + db_[j])) continue;  // never beats sending both to the diagonal
      relax(node_of_b(j), d + std::max(0.0, c + pi_[i] - pi_[node_of_b(j)]), i, c);
    }
  }
}

std::int32_t DiagonalFlow::home_leaf(std::uint32_t i) {
  if (home_leaf_.empty()) home_leaf_.assign(n_, -1);
  if (home_leaf_[i] >= 0) return home_leaf_[i];
  const auto nodes = tree_b_->nodes();
  std::int32_t k = 0;
  while (nodes[k].left >= 0) {
    const auto& left = nodes[nodes[k].left];
    const auto& right = nodes[nodes[k].right];
    k = tree_b_->box_distance(left, pa_[i]) <= tree_b_->box_distance(right, pa_[i]) ? nodes[k].left : nodes[k].right;
  }
  return home_leaf_[i] = k;
}

void DiagonalFlow::update_box_maxima(std::uint32_t j) {
  for (std::int32_t k = leaf_of_b_[j]; k >= 0 && recompute_box(k); k = box_parent_[k]) {
  }
}

double DiagonalFlow::primal_cost() const {
  double cost = 0;
  for (std::uint32_t i = 0; i < n_; ++i) cost += mate_a_[i] >= 0 ? mate_cost_a_[i] : da_[i];
  for (std::uint32_t j = 0; j < m_; ++j)
    if (mate_b_[j] < 0) cost += db_[j];
  return cost;
}

void DiagonalFlow::refresh(std::uint32_t node) {
  // a_i is filed in HB's stream while it is sent to the diagonal, b_j in HA's while it is not fed
  // from it; the hubs are never filed.
  if (is_a(node)) {
    if (mate_a_[node] == kDiagonal) {
      hub_b_.set(node, -da_[node] - pi_[node]);
    } else {
      hub_b_.erase(node);
    }
  } else if (is_b(node)) {
    const std::uint32_t j = b_of_node(node);
    if (mate_b_[j] != kDiagonal) {
      hub_a_.set(j, db_[j] - pi_[node]);
    } else {
      hub_a_.erase(j);
    }
  }
}

bool DiagonalFlow::is_sink(std::uint32_t v) const {
  if (is_b(v)) return mate_b_[b_of_node(v)] == kNone;
  if (v == hb_) return a_to_diagonal_ + flow_hub_ < static_cast<std::int64_t>(n_);
  return false;
}

void DiagonalFlow::push(double key, std::int64_t id) { heap_.push({key, id}); }

void DiagonalFlow::push_box(std::uint32_t row, std::int32_t node, double key) {
  boxes_.push_back({row, node});
  push(key, kBoxBase + static_cast<std::int64_t>(boxes_.size() - 1));
}

void DiagonalFlow::relax(std::uint32_t v, double d, std::uint32_t from, double cost) {
  if (final_[v] == run_) return;
  if (seen_[v] == run_ && dist_[v] <= d) return;
  seen_[v] = run_;
  dist_[v] = d;
  pred_[v] = from;
  pred_cost_[v] = cost;
  push(d, v);
  // Nothing left in the heap is below current_: a sink reached at that distance is a shortest path.
  if (d <= current_ && early_ < 0 && is_sink(v)) early_ = v;
}

KeyedIndex& DiagonalFlow::stream_arcs(int stream) { return stream == kStreamHa ? hub_a_ : hub_b_; }

std::uint32_t DiagonalFlow::stream_node(int stream, std::uint32_t index) const {
  return stream == kStreamHa ? node_of_b(index) : index;
}

std::uint32_t DiagonalFlow::stream_hub(int stream) const { return stream == kStreamHa ? ha_ : hb_; }

bool DiagonalFlow::skip_settled(int stream) {
  KeyedIndex& arcs = stream_arcs(stream);
  while (!arcs.walk_done() && final_[stream_node(stream, arcs.walk_head().second)] == run_) arcs.walk_next();
  return !arcs.walk_done();
}

void DiagonalFlow::push_stream(int stream) {
  if (!skip_settled(stream)) return;
  push(hub_dist_[stream] + std::max(0.0, pi_[stream_hub(stream)] + stream_arcs(stream).walk_head().first),
       stream_entry(stream));
}

void DiagonalFlow::start_stream(int stream, double d) {
  hub_dist_[stream] = d;
  stream_arcs(stream).walk_start();
  push_stream(stream);
}

void DiagonalFlow::pop_stream(int stream) {
  if (!skip_settled(stream)) return;
  KeyedIndex& arcs = stream_arcs(stream);
  const auto [key, index] = arcs.walk_head();
  const std::uint32_t hub = stream_hub(stream);
  const double arc_cost = stream == kStreamHa ? db_[index] : -da_[index];
  relax(stream_node(stream, index), hub_dist_[stream] + std::max(0.0, pi_[hub] + key), hub, arc_cost);
  arcs.walk_next();
  push_stream(stream);
}

void DiagonalFlow::scan(std::uint32_t u, double d) {
  if (is_a(u) && sparse_) {
    const double pu = pi_[u];
    for (std::uint32_t k = cand_start_[u]; k < cand_start_[u + 1]; ++k) {
      const std::uint32_t j = cand_[k];
      if (mate_a_[u] == static_cast<std::int64_t>(j)) continue;
      const double c = cost(u, j);
      if (!(c < da_[u] + db_[j])) continue;
      relax(node_of_b(j), d + std::max(0.0, c + pu - pi_[node_of_b(j)]), u, c);
    }
    if (mate_a_[u] != kDiagonal) relax(hb_, d + std::max(0.0, da_[u] + pu - pi_[hb_]), u, da_[u]);
  } else if (is_a(u)) {
    if (!tree_b_->nodes().empty()) {
      // The tree entered from a_u's home leaf upwards: that leaf, then the sibling of each box on
      // the way to the root. The same boxes as from the root down, each by its own key, without
      // keying the boxes on the way, which every settled row used to open.
      const auto nodes = tree_b_->nodes();
      const auto enter = [&](std::int32_t k) {
        const double key = box_key(u, k);
        if (key <= d) {
          open_box(u, k);
        } else if (key < kInf) {
          push_box(u, k, key);
        }
      };
      std::int32_t k = home_leaf(u);
      enter(k);
      for (std::int32_t parent; (parent = box_parent_[k]) >= 0; k = parent)
        enter(nodes[parent].left == k ? nodes[parent].right : nodes[parent].left);
    }
    if (mate_a_[u] != kDiagonal) relax(hb_, d + std::max(0.0, da_[u] + pi_[u] - pi_[hb_]), u, da_[u]);
  } else if (is_b(u)) {
    const std::uint32_t j = b_of_node(u);
    const std::int64_t mate = mate_b_[j];
    if (mate >= 0) {
      const auto i = static_cast<std::uint32_t>(mate);
      relax(i, d + std::max(0.0, -mate_cost_a_[i] + pi_[u] - pi_[i]), u, -mate_cost_a_[i]);
    } else if (mate == kDiagonal) {
      relax(ha_, d + std::max(0.0, -db_[j] + pi_[u] - pi_[ha_]), u, -db_[j]);
    }
  } else if (u == ha_) {
    relax(hb_, d + std::max(0.0, pi_[ha_] - pi_[hb_]), u, 0);
    start_stream(kStreamHa, d);
  } else {
    if (flow_hub_ > 0) relax(ha_, d + std::max(0.0, pi_[hb_] - pi_[ha_]), u, 0);
    start_stream(kStreamHb, d);
  }
}

bool DiagonalFlow::dijkstra(std::uint32_t source) {
  ++run_;
  heap_.clear();
  boxes_.clear();
  early_ = -1;
  current_ = -kInf;
  finalized_.clear();
  seen_[source] = run_;
  dist_[source] = 0;
  push(0.0, source);
  std::int64_t target = -1;
  while (!heap_.empty()) {
    const auto [d, id] = heap_.pop();
    if (is_box_entry(id)) {
      const BoxEntry box = boxes_[static_cast<std::size_t>(id - kBoxBase)];
      current_ = d;
      open_box(box.row, box.node);
      if (early_ >= 0) {
        target = early_;
        break;
      }
      continue;
    }
    if (is_stream_entry(id)) {
      pop_stream(stream_of_entry(id));
      continue;
    }
    const auto u = static_cast<std::uint32_t>(id);
    if (final_[u] == run_ || d > dist_[u]) continue;
    final_[u] = run_;
    finalized_.push_back(u);
    ++settled_;
    if (is_b(u) && !sparse_) {
      for (std::int32_t k = leaf_of_b_[b_of_node(u)]; k >= 0; k = box_parent_[k]) {
        if (box_run_[k] != run_) box_run_[k] = run_, box_done_[k] = 0;
        ++box_done_[k];
      }
    }
    if (u != source && is_sink(u)) {
      target = u;
      break;
    }
    current_ = d;
    scan(u, d);
    if (early_ >= 0) {
      target = early_;
      break;
    }
  }
  if (target < 0) return false;
  // Early exit: every settled node is at distance <= total, the rest keep their potentials.
  const double total = dist_[target];
  for (const std::uint32_t v : finalized_) pi_[v] -= total - dist_[v];
  augment(source, static_cast<std::uint32_t>(target));
  for (const std::uint32_t v : finalized_) refresh(v);
  if (!sparse_)
    for (const std::uint32_t v : finalized_)
      if (is_b(v)) update_box_maxima(b_of_node(v));
  return true;
}

void DiagonalFlow::augment(std::uint32_t source, std::uint32_t target) {
  // Augment along the path, source to target.
  std::vector<std::uint32_t>& path = path_;
  path.clear();
  for (auto v = static_cast<std::uint32_t>(target);; v = pred_[v]) {
    path.push_back(v);
    if (v == source) break;
  }
  std::reverse(path.begin(), path.end());
  std::int64_t amount = 1;
  if (path.size() == 2 && path[0] == ha_ && path[1] == hb_) {
    const std::int64_t supply = static_cast<std::int64_t>(m_) - b_from_diagonal_ - flow_hub_;
    const std::int64_t demand = static_cast<std::int64_t>(n_) - a_to_diagonal_ - flow_hub_;
    amount = std::max<std::int64_t>(1, std::min(supply, demand));
  }
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const std::uint32_t u = path[k], v = path[k + 1];
    if (is_a(u) && is_b(v)) {  // a_u takes b_v
      mate_a_[u] = b_of_node(v), mate_b_[b_of_node(v)] = u, mate_cost_a_[u] = pred_cost_[v];
    } else if (is_a(u) && v == hb_) {  // a_u goes to the diagonal
      mate_a_[u] = kDiagonal, ++a_to_diagonal_;
    } else if (u == ha_ && is_b(v)) {  // b_v is fed by the diagonal
      mate_b_[b_of_node(v)] = kDiagonal, ++b_from_diagonal_;
    } else if (u == ha_ && v == hb_) {
      flow_hub_ += amount;
    } else if (u == hb_ && v == ha_) {
      --flow_hub_;
    } else if (u == hb_ && is_a(v)) {  // a_v leaves the diagonal
      if (mate_a_[v] == kDiagonal) mate_a_[v] = kNone;
      --a_to_diagonal_;
    } else if (v == ha_) {  // b_u no longer fed by the diagonal
      if (mate_b_[b_of_node(u)] == kDiagonal) mate_b_[b_of_node(u)] = kNone;
      --b_from_diagonal_;
    } else {  // b_u -> a_v: the pair (a_v, b_u) is undone
      if (mate_a_[v] == static_cast<std::int64_t>(b_of_node(u))) mate_a_[v] = kNone;
      if (mate_b_[b_of_node(u)] == static_cast<std::int64_t>(v)) mate_b_[b_of_node(u)] = kNone;
    }
  }
  for (const std::uint32_t v : path) refresh(v);
  ++augmentations_;
}

double DiagonalFlow::dual_bound() const {
  // LP duality on the assignment form (every arc but HA -> HB has capacity 1, which changes
  // nothing as each a_i supplies and each b_j takes one unit): demand * potential minus supply *
  // potential, minus each capacity-1 arc's negative reduced cost. The pair arcs all have reduced
  // cost >= 0 (the searches scan them all; pairs with c_ij >= da_i + db_j are left out of the
  // problem, which keeps its optimum). The hub arcs into a point already matched to the diagonal
  // are never scanned (they only close cycles) and may go negative: charged here.
  double dual = static_cast<double>(n_) * pi_[hb_] - static_cast<double>(m_) * pi_[ha_];
  for (std::uint32_t i = 0; i < n_; ++i) dual -= pi_[i] + std::max(0.0, -(da_[i] + pi_[i] - pi_[hb_]));
  for (std::uint32_t j = 0; j < m_; ++j) {
    const double pi_b = pi_[node_of_b(j)];
    dual += pi_b - std::max(0.0, -(db_[j] + pi_[ha_] - pi_b));
  }
  // HA -> HB is unbounded: a negative reduced cost there (beyond rounding) voids the bound.
  if (pi_[ha_] - pi_[hb_] < -1e-12 * (std::fabs(pi_[ha_]) + std::fabs(pi_[hb_]))) return -kInf;
  return dual - pair_penalty_;
}

bool DiagonalFlow::augment_all(double accept_ratio) {
  // With accept_ratio > 1, every few augmentations: the flow with its free points sent to the
  // diagonal is a matching (primal_cost() counts them so), the potentials a dual bound.
  const std::size_t stride = 1 + (n_ + m_) / 256;
  std::size_t since = 0;
  const auto good_enough = [&] {
    if (accept_ratio <= 1 || ++since < stride) return false;
    since = 0;
    return finished_within(accept_ratio, &DiagonalFlow::complete_free_rows);
  };
  while (static_cast<std::int64_t>(m_) - b_from_diagonal_ - flow_hub_ > 0) {
    if (!dijkstra(ha_)) throw std::logic_error("diagonal flow: no augmenting path from the diagonal");
    if (good_enough()) return true;
  }
  for (std::uint32_t i = 0; i < n_; ++i) {
    if (mate_a_[i] != kNone) continue;
    if (!dijkstra(i)) throw std::logic_error("diagonal flow: no augmenting path");
    if (good_enough()) return true;
  }
  return false;
}

bool DiagonalFlow::finished_within(double accept_ratio, bool (DiagonalFlow::*finish)(double)) {
  lower_free_rows();
  const double lower = dual_bound();
  return lower > 0 && (this->*finish)(accept_ratio * lower);
}

bool DiagonalFlow::complete_free_rows(double target) {
  // The flow as it is (free rows on the diagonal) when that is enough. Otherwise each free row may
  // take a candidate b_j instead, sending b_j's partner to the diagonal (or b_j leaving it): the
  // best such change per row, each b_j at most once, in row order. Applied only when the matching
  // then costs <= target.
  if (primal_cost() <= target) return true;
  struct Swap {
    std::uint32_t row, column;
    double cost;
  };
  std::vector<Swap> swaps;
  std::vector<std::uint8_t> used(m_, 0);
  double upper = primal_cost();
  for (std::uint32_t i = 0; i < n_; ++i) {
    if (mate_a_[i] != kNone) continue;
    double best_gain = 0;
    Swap best{i, 0, 0};
    for (std::uint32_t k = cand_start_[i]; k < cand_start_[i + 1]; ++k) {
      const std::uint32_t j = cand_[k];
      if (used[j]) continue;
      const double c = cost(i, j);
      if (!(c < da_[i] + db_[j])) continue;
      const std::int64_t mate = mate_b_[j];
      const double before = da_[i] + (mate >= 0 ? mate_cost_a_[mate] : db_[j]);
      const double after = c + (mate >= 0 ? da_[mate] : 0.0);
      if (before - after > best_gain) best_gain = before - after, best = {i, j, c};
    }
    if (best_gain == 0) continue;
    used[best.column] = 1;
    swaps.push_back(best);
    upper -= best_gain;
  }
  if (!(upper <= target)) return false;
  for (const Swap& s : swaps) {
    const std::int64_t mate = mate_b_[s.column];
    if (mate >= 0) {
      mate_a_[mate] = kDiagonal, ++a_to_diagonal_;
    } else if (mate == kDiagonal) {
      --b_from_diagonal_;
    }
    mate_a_[s.row] = s.column, mate_b_[s.column] = s.row, mate_cost_a_[s.row] = s.cost;
  }
  return true;
}

bool DiagonalFlow::match_free_points_apart(double target) {
  // Loose points: free, or on the diagonal (they may pair up among themselves instead).
  std::vector<PlanePoint> loose_a, loose_b;
  std::vector<std::uint32_t> row_of, column_of;
  double cost_apart = primal_cost();  // loose points counted on the diagonal: replaced below
  const auto points_b = tree_b_->points();
  for (std::uint32_t i = 0; i < n_; ++i)
    if (mate_a_[i] < 0) loose_a.push_back(pa_[i]), row_of.push_back(i), cost_apart -= da_[i];
  for (std::uint32_t j = 0; j < m_; ++j)
    if (mate_b_[j] < 0) loose_b.push_back(points_b[j]), column_of.push_back(j), cost_apart -= db_[j];
  if (loose_a.empty() || loose_b.empty()) return false;  // nothing to pair: the flow's own matching
  DiagonalFlow apart(loose_a, loose_b, power_);
  apart.solve();
  cost_apart += apart.primal_cost();
  if (!(cost_apart <= target)) return false;
  for (std::uint32_t k = 0; k < row_of.size(); ++k) {
    const std::uint32_t i = row_of[k];
    if (mate_a_[i] == kDiagonal) --a_to_diagonal_;
    const std::int64_t j = apart.mate_of_a(k);
    if (j >= 0) {
      const std::uint32_t column = column_of[static_cast<std::size_t>(j)];
      mate_a_[i] = column, mate_cost_a_[i] = cost(i, column);
    } else {
      mate_a_[i] = kDiagonal, ++a_to_diagonal_;
    }
  }
  for (std::uint32_t k = 0; k < column_of.size(); ++k) {
    const std::uint32_t j = column_of[k];
    if (mate_b_[j] == kDiagonal) --b_from_diagonal_;
    const std::int64_t i = apart.mate_of_b(k);
    if (i >= 0) {
      mate_b_[j] = row_of[static_cast<std::size_t>(i)];
    } else {
      mate_b_[j] = kDiagonal, ++b_from_diagonal_;
    }
  }
  return true;
}

void DiagonalFlow::lower_free_rows() {
  // A free row has no arc in, so its potential is bound only by its arcs out: the least value
  // that keeps them all >= 0 (one of them tight) is feasible and raises the dual bound by what
  // the row's cheapest way out costs, where the potential it had may be far above that.
  std::vector<std::pair<double, std::uint32_t>> top;
  for (std::uint32_t i = 0; i < n_; ++i) {
    if (mate_a_[i] != kNone) continue;
    const double diagonal = da_[i] - pi_[hb_];  // cost - pi(head) of the arc to the diagonal
    cheapest_pair_prices(i, 1, diagonal, top);
    pi_[i] = -(top.empty() ? diagonal : std::min(diagonal, top.front().first));
  }
}

void DiagonalFlow::solve_complete(double accept_ratio) {
  if (!started_) greedy_start();
  sparse_ = false;
  completed_ = true;
  recompute_all_boxes();
  augment_all(accept_ratio);
}

void DiagonalFlow::solve(double accept_ratio) {
  // Rounds of "add the violated arcs, free their rows, route them again" before the complete
  // graph takes over: a round costs one check of every pair plus sparse searches for the freed
  // rows, less than complete-graph searches for them unless only a couple are left. On the LAMMPS
  // PD1 pairs exact solves take 4-15 rounds with three arcs added per violating row; past
  // kMaxRounds the complete graph finishes.
  constexpr std::size_t kMaxRounds = 24, kFewRows = 2;
  // The line start is taken for W1 and W2 at any size where most points lie on one death line.
  // Where the staged solve (repair rounds) is measured faster when it is not: W1 and W2 up to a few
  // thousand points a side; above that W1 only on a common death line (a one-off run on 20 000
  // jittered copies of a LAMMPS PD1, before the line start: 35.9 s against 191.5 s for the
  // complete-graph searches alone; the 50 000-point random pair of large_inputs_test: 108 s against
  // 23 s, so not there). Other q keep the complete graph: their costs are capped at
  // ArcPower::kCap, and potentials near the cap leave the check's tolerance meaningless.
  constexpr std::size_t kStagedMaxPoints = 8000;
  constexpr double kLineShare = 0.5;
  const bool small = n_ + m_ <= 2 * kStagedMaxPoints;
  const double line_share = n_ == 0 || m_ == 0 ? 0 : share_on_common_line(pa_, tree_b_->points());
  const bool on_line = power_.is_plain() && line_share >= kLineShare;
  const bool staged = power_.is_plain() && (small || (power_.is_identity() && on_line));
  if (n_ == 0 || m_ == 0 || !(staged || on_line)) {
    solve_complete();
    return;
  }
  // The band doubles until the programme's path keeps off its edges (or holds every column, or
  // the next one would pass kMaxBandCells).
  LineAlignment alignment;
  for (std::uint32_t width = kBand;; width *= 2) {
    alignment = sorted_birth_alignment(
        pa_, tree_b_->points(), da_, db_, [this](std::uint32_t i, std::uint32_t j) { return cost(i, j); }, width);
    const std::size_t cells = static_cast<std::size_t>(std::max(n_, m_)) * (4 * std::size_t{width} + 1);
    if (alignment.optimal || !on_line || width >= std::max(n_, m_) || cells > kMaxBandCells) break;
  }
  build_candidates(alignment, on_line);
  sparse_ = true;
  // A band that stopped growing before its path kept off its edges may still hold the optimum (under
  // q = 1 equal-cost paths abound): line_start() finds out.
  if (on_line && line_start(alignment)) {
    // Certified over every pair: the off-line points, all that is left, are routed by searches on
    // the complete graph, which keep the certificate (the sparse searches would lose it on the
    // arcs into their flat-cost windows, and repair rounds then reroute hundreds of rows).
    pair_penalty_ = 0;
    // Approximate: the line's points are matched optimally among themselves already; with the
    // loose points matched apart, optimally too, the matching may already be within the ratio.
    if (accept_ratio > 1 && finished_within(accept_ratio, &DiagonalFlow::match_free_points_apart)) return;
    solve_complete(accept_ratio);
    return;
  }
  if (!staged) {
    solve_complete();
    return;
  }
  if (on_line) add_nearest_candidates(std::nullopt);  // the line start failed: every point's
  greedy_start();
  augment_all();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> extra;
  for (;;) {
    recompute_all_boxes();
    check_pairs();
    ++rounds_;
    if (violations_.empty()) break;  // certified on every pair
    // pair_penalty_ now counts every violation: dual_bound() is a valid lower bound.
    if (accept_ratio > 1 && dual_bound() > 0 && primal_cost() <= accept_ratio * dual_bound()) break;
    if (rounds_ > kMaxRounds || violations_.size() <= kFewRows) {
      repair_violations();
      pair_penalty_ = 0;
      solve_complete();
      return;
    }
    extra.clear();
    for (const Violation& v : violations_) extra.push_back({v.row, v.column});
    add_candidates(extra);
    repair_violations();
    augment_all();
  }
  sparse_ = false;
}

void DiagonalFlow::build_candidates(const LineAlignment& alignment, bool off_line_only) {
  cand_start_.assign(n_ + 1, 0);
  cand_.clear();
  add_candidates(alignment_candidates(alignment));
  add_nearest_candidates(off_line_only ? std::optional<double>(alignment.line) : std::nullopt);
}

void DiagonalFlow::add_nearest_candidates(std::optional<double> skip_line) {
  // Each point's nearest neighbours on the other side, that side brought to scale f first. The
  // line start needs them for the off-line points only (its line points have the programme's
  // pairs, and the certification adds whatever else its potentials need).
  constexpr std::size_t kNearest = 4;  // includes the row reduction's choices
  std::vector<std::pair<std::uint32_t, std::uint32_t>> arcs;
  const auto points_b = tree_b_->points();
  std::vector<std::uint32_t> near;
  const auto add_nearest = [&](double f) {
    for (std::uint32_t i = 0; i < n_; ++i) {
      if (skip_line && pa_[i].y == *skip_line) continue;
      tree_b_->nearest({pa_[i].x * f, pa_[i].y * f}, kNearest, near, i);
      for (const std::uint32_t j : near) arcs.push_back({i, j});
    }
    for (std::uint32_t j = 0; j < m_; ++j) {
      if (skip_line && points_b[j].y == *skip_line) continue;
      tree_a_->nearest({points_b[j].x / f, points_b[j].y / f}, kNearest, near, j);
      for (const std::uint32_t i : near) arcs.push_back({i, j});
    }
  };
  add_nearest(1);
  if (!skip_line)
    if (const double f = quantile_scale(pa_, points_b); f != 1) add_nearest(f);
  add_candidates(arcs);
}

void DiagonalFlow::add_candidates(std::span<const std::pair<std::uint32_t, std::uint32_t>> arcs) {
  std::vector<std::uint32_t> count(n_ + 1, 0);
  for (std::uint32_t i = 0; i < n_; ++i) count[i] = cand_start_[i + 1] - cand_start_[i];
  for (const auto& [i, j] : arcs) ++count[i];
  std::vector<std::uint32_t> start(n_ + 1, 0);
  for (std::uint32_t i = 0; i < n_; ++i) start[i + 1] = start[i] + count[i];
  std::vector<std::uint32_t> heads(start[n_]);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t i = 0; i < n_; ++i)
    for (std::uint32_t k = cand_start_[i]; k < cand_start_[i + 1]; ++k) heads[fill[i]++] = cand_[k];
  for (const auto& [i, j] : arcs) heads[fill[i]++] = j;
  // Sort and deduplicate each row in place, then compact.
  cand_.clear();
  cand_.reserve(heads.size());
  for (std::uint32_t i = 0; i < n_; ++i) {
    const auto first = heads.begin() + start[i], last = heads.begin() + start[i + 1];
    std::sort(first, last);
    const auto end = std::unique(first, last);
    cand_start_[i] = static_cast<std::uint32_t>(cand_.size());
    cand_.insert(cand_.end(), first, end);
  }
  cand_start_[n_] = static_cast<std::uint32_t>(cand_.size());
}

void DiagonalFlow::cheapest_pair_prices(std::uint32_t i, std::size_t count, double limit,
                                        std::vector<std::pair<double, std::uint32_t>>& top) {
  top.clear();
  const auto nodes = tree_b_->nodes();
  if (nodes.empty()) return;
  const auto order = tree_b_->order();
  const auto points = tree_b_->points();
  const PlanePoint a = pa_[i];
  const auto threshold = [&] { return top.size() < count ? limit : top.back().first; };
  box_stack_.assign(1, 0);
  while (!box_stack_.empty()) {
    const std::int32_t k = box_stack_.back();
    box_stack_.pop_back();
    const auto& box = nodes[k];
    if (!(box_price_bound(i, k) < threshold())) continue;
    if (box.left >= 0) {
      // Nearer child last: popped first, it lowers the threshold sooner.
      const double dl = tree_b_->box_distance(nodes[box.left], a), dr = tree_b_->box_distance(nodes[box.right], a);
      if (dl < dr) {
        box_stack_.push_back(box.right), box_stack_.push_back(box.left);
      } else {
        box_stack_.push_back(box.left), box_stack_.push_back(box.right);
      }
      continue;
    }
    for (std::uint32_t s = box.begin; s < box.end; ++s) {
      const std::uint32_t j = order[s];
      const double cj = power_(linf_distance(a, points[j]));
      if (!(cj < da_[i] + db_[j])) continue;
      const double v = cj - pi_[node_of_b(j)];
      if (!(v < threshold())) continue;
      if (top.size() == count) top.pop_back();
      top.insert(std::upper_bound(top.begin(), top.end(), std::make_pair(v, j)), {v, j});
    }
  }
}

void DiagonalFlow::check_pairs(std::size_t top_arcs) {
  violations_.clear();
  pair_penalty_ = 0;
  const auto points = tree_b_->points();
  std::vector<std::pair<double, std::uint32_t>> top;  // the row's most negative c_ij - pi(b_j), ascending
  for (std::uint32_t i = 0; i < n_; ++i) {
    // The smallest c_ij - pi(b_j) below -pi(a_i): negative reduced costs.
    const PlanePoint a = pa_[i];
    const double pa = pi_[i];
    cheapest_pair_prices(i, top_arcs, -pa, top);
    if (top.empty()) continue;
    const double amount = -(top.front().first + pa);
    pair_penalty_ += amount;
    // Beyond rounding: a real violation, repaired; below it, only counted.
    // Rounding in c + pi(a) - pi(b) is relative to the terms' size, not to 1 (costs can be 1e-20
    // of the potentials, as under `sentinel` with tiny forces).
    const std::uint32_t jb = top.front().second;
    const double size = std::fabs(pa) + std::fabs(pi_[node_of_b(jb)]) + power_(linf_distance(a, points[jb]));
    if (amount > 1e-14 * size)
      for (std::size_t t = 0; t < top.size(); ++t) violations_.push_back({i, top[t].second, t == 0 ? amount : 0.0});
  }
}

void DiagonalFlow::repair_violations() {
  for (const Violation& v : violations_) {
    if (v.amount == 0) continue;  // a further arc of a row listed before
    const std::uint32_t i = v.row;
    pi_[i] += v.amount;  // every pair arc out of a_i now has reduced cost >= 0, the best one 0
    pair_penalty_ -= v.amount;
    const std::int64_t mate = mate_a_[i];
    if (mate >= 0) {
      mate_b_[static_cast<std::size_t>(mate)] = kNone;
      refresh(node_of_b(static_cast<std::uint32_t>(mate)));
    } else if (mate == kDiagonal) {
      --a_to_diagonal_;
    }
    mate_a_[i] = kNone;
    refresh(i);
    ++repaired_;
  }
  violations_.clear();
}

}  // namespace fnet
