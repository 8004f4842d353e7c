#include "common/distance/shortest_paths.hpp"

#include <algorithm>
#include <limits>

#include "common/distance/infinity.hpp"
#include "common/distance/work_deadline.hpp"

namespace fnet {

namespace {}  // namespace

ShortestPaths::ShortestPaths(FlowState& flow, HubArcs& hubs, PairOracle& oracle, const CandidateArcs& candidates)
    : flow_(flow),
      hubs_(hubs),
      oracle_(oracle),
      candidates_(candidates),
      box_run_(oracle.tree_b().nodes().size(), 0),
      box_done_(oracle.tree_b().nodes().size(), 0),
      dist_(flow.nodes(), kInf),
      pred_cost_(flow.nodes(), 0),
      pred_(flow.nodes(), 0),
      seen_(flow.nodes(), 0),
      final_(flow.nodes(), 0),
      heap_(flow.nodes()) {}

void ShortestPaths::push_box(std::uint32_t row, std::int32_t node, double key) {
  boxes_.push_back({row, node});
  push(key, kBoxBase + static_cast<std::int64_t>(boxes_.size() - 1));
}

void ShortestPaths::relax(std::uint32_t v, double d, std::uint32_t from, double cost) {
  if (final_[v] == run_) return;
  if (seen_[v] == run_ && dist_[v] <= d) return;
  seen_[v] = run_;
  dist_[v] = d;
  pred_[v] = from;
  pred_cost_[v] = cost;
  push(d, v);
  // Nothing left in the heap is below current_: a sink reached at that distance is a shortest path.
  if (d <= current_ && early_ < 0 && flow_.is_sink(v)) early_ = v;
}

bool ShortestPaths::skip_settled(int stream) {
  KeyedIndex& arcs = hubs_.arcs(stream);
  while (!arcs.walk_done() && final_[HubArcs::node(flow_, stream, arcs.walk_head().second)] == run_) arcs.walk_next();
  return !arcs.walk_done();
}

void ShortestPaths::push_stream(int stream) {
  if (!skip_settled(stream)) return;
  push(hub_dist_[stream] + std::max(0.0, flow_.pi[HubArcs::hub(flow_, stream)] + hubs_.arcs(stream).walk_head().first),
       stream_entry(stream));
}

void ShortestPaths::start_stream(int stream, double d) {
  hub_dist_[stream] = d;
  hubs_.arcs(stream).walk_start();
  push_stream(stream);
}

void ShortestPaths::pop_stream(int stream) {
  if (!skip_settled(stream)) return;
  KeyedIndex& arcs = hubs_.arcs(stream);
  const auto [key, index] = arcs.walk_head();
  const std::uint32_t hub = HubArcs::hub(flow_, stream);
  relax(HubArcs::node(flow_, stream, index), hub_dist_[stream] + std::max(0.0, flow_.pi[hub] + key), hub,
        HubArcs::arc_cost(flow_, stream, index));
  arcs.walk_next();
  push_stream(stream);
}

double ShortestPaths::box_key(std::uint32_t i, std::int32_t node) const {
  const auto& box = oracle_.tree_b().nodes()[node];
  if (box_run_[node] == run_ && box_done_[node] == box.end - box.begin) return kInf;  // all settled
  const double bound = oracle_.price_bound(i, node);
  if (bound == kInf) return kInf;
  return dist_[i] + std::max(0.0, bound + flow_.pi[i]);
}

void ShortestPaths::open_box(std::uint32_t i, std::int32_t node) {
  // Boxes whose key is not above the current distance would pop next anyway: open them at once.
  const auto nodes = oracle_.tree_b().nodes();
  const auto order = oracle_.tree_b().order();
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
      if (flow_.mate_a[i] == static_cast<std::int64_t>(j)) continue;
      const double c = flow_.cost(i, j);
      if (!(c < flow_.da[i] + flow_.db[j])) continue;  // never beats sending both to the diagonal
      relax(flow_.node_of_b(j), d + std::max(0.0, c + flow_.pi[i] - flow_.pi[flow_.node_of_b(j)]), i, c);
    }
  }
}

void ShortestPaths::scan_boxes(std::uint32_t u, double d) {
  // The tree entered from a_u's home leaf upwards: that leaf, then the sibling of each box on the
  // way to the root. The same boxes as from the root down, each by its own key, without keying
  // the boxes on the way.
  const auto nodes = oracle_.tree_b().nodes();
  if (nodes.empty()) return;
  const auto enter = [&](std::int32_t k) {
    const double key = box_key(u, k);
    if (key <= d) {
      open_box(u, k);
    } else if (key < kInf) {
      push_box(u, k, key);
    }
  };
  std::int32_t k = oracle_.home_leaf(u);
  enter(k);
  for (std::int32_t parent; (parent = oracle_.parent(k)) >= 0; k = parent)
    enter(nodes[parent].left == k ? nodes[parent].right : nodes[parent].left);
}

void ShortestPaths::scan(std::uint32_t u, double d) {
  FlowState& f = flow_;
  if (f.is_a(u)) {
    if (sparse_) {
      const double pu = f.pi[u];
      for (const std::uint32_t j : candidates_.row(u)) {
        if (f.mate_a[u] == static_cast<std::int64_t>(j)) continue;
        const double c = f.cost(u, j);
        if (!(c < f.da[u] + f.db[j])) continue;
        relax(f.node_of_b(j), d + std::max(0.0, c + pu - f.pi[f.node_of_b(j)]), u, c);
      }
    } else {
      scan_boxes(u, d);
    }
    if (f.mate_a[u] != FlowState::kDiagonal) relax(f.hb, d + std::max(0.0, f.da[u] + f.pi[u] - f.pi[f.hb]), u, f.da[u]);
  } else if (f.is_b(u)) {
    const std::uint32_t j = f.b_of_node(u);
    const std::int64_t mate = f.mate_b[j];
    if (mate >= 0) {
      const auto i = static_cast<std::uint32_t>(mate);
      relax(i, d + std::max(0.0, -f.mate_cost_a[i] + f.pi[u] - f.pi[i]), u, -f.mate_cost_a[i]);
    } else if (mate == FlowState::kDiagonal) {
      relax(f.ha, d + std::max(0.0, -f.db[j] + f.pi[u] - f.pi[f.ha]), u, -f.db[j]);
    }
  } else if (u == f.ha) {
    relax(f.hb, d + std::max(0.0, f.pi[f.ha] - f.pi[f.hb]), u, 0);
    start_stream(HubArcs::kFromHa, d);
  } else {
    if (f.flow_hub > 0) relax(f.ha, d + std::max(0.0, f.pi[f.hb] - f.pi[f.ha]), u, 0);
    start_stream(HubArcs::kFromHb, d);
  }
}

bool ShortestPaths::route(std::uint32_t source) {
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
    check_work_deadline();
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
    if (flow_.is_b(u) && !sparse_) {
      for (std::int32_t k = oracle_.leaf_of_b(flow_.b_of_node(u)); k >= 0; k = oracle_.parent(k)) {
        if (box_run_[k] != run_) box_run_[k] = run_, box_done_[k] = 0;
        ++box_done_[k];
      }
    }
    if (u != source && flow_.is_sink(u)) {
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
  for (const std::uint32_t v : finalized_) flow_.pi[v] -= total - dist_[v];
  augment(source, static_cast<std::uint32_t>(target));
  for (const std::uint32_t v : finalized_) hubs_.refresh(flow_, v);
  if (!sparse_)
    for (const std::uint32_t v : finalized_)
      if (flow_.is_b(v)) oracle_.update_maxima(flow_.b_of_node(v));
  return true;
}

void ShortestPaths::augment(std::uint32_t source, std::uint32_t target) {
  path_.clear();
  for (auto v = target;; v = pred_[v]) {
    path_.push_back(v);
    if (v == source) break;
  }
  std::reverse(path_.begin(), path_.end());
  flow_.augment(path_, pred_cost_);
  for (const std::uint32_t v : path_) hubs_.refresh(flow_, v);
  ++augmentations_;
}

}  // namespace fnet
