#include "common/diagonal_flow.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

namespace fnet {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::int64_t kGenerator[2] = {-1, -2};  // heap ids of the two hubs' lazy arc streams
}  // namespace

DiagonalFlow::DiagonalFlow(std::vector<double> diagonal_a, std::vector<double> diagonal_b, std::vector<Arc> arcs)
    : n_(static_cast<std::uint32_t>(diagonal_a.size())), m_(static_cast<std::uint32_t>(diagonal_b.size())),
      ha_(n_ + m_), hb_(n_ + m_ + 1), da_(std::move(diagonal_a)), db_(std::move(diagonal_b)),
      mate_a_(n_, kNone), mate_b_(m_, kNone), mate_cost_a_(n_, 0), pi_(n_ + m_ + 2, 0.0),
      key_(n_ + m_ + 2, std::numeric_limits<double>::quiet_NaN()), dist_(n_ + m_ + 2, kInf),
      pred_cost_(n_ + m_ + 2, 0), pred_(n_ + m_ + 2, 0), seen_(n_ + m_ + 2, 0), final_(n_ + m_ + 2, 0) {
  rebuild_rows(std::move(arcs));
  for (std::uint32_t j = 0; j < m_; ++j) refresh(n_ + j);
}

void DiagonalFlow::rebuild_rows(std::vector<Arc> arcs) {
  std::sort(arcs.begin(), arcs.end(), [](const Arc& x, const Arc& y) {
    return x.row != y.row ? x.row < y.row : x.col < y.col;
  });
  arcs.erase(std::unique(arcs.begin(), arcs.end(),
                         [](const Arc& x, const Arc& y) { return x.row == y.row && x.col == y.col; }),
             arcs.end());
  row_start_.assign(n_ + 1, 0);
  row_col_.resize(arcs.size());
  row_cost_.resize(arcs.size());
  for (const Arc& arc : arcs) ++row_start_[arc.row + 1];
  for (std::uint32_t i = 0; i < n_; ++i) row_start_[i + 1] += row_start_[i];
  for (std::size_t k = 0; k < arcs.size(); ++k) row_col_[k] = arcs[k].col, row_cost_[k] = arcs[k].cost;
}

bool DiagonalFlow::has_arc(std::uint32_t row, std::uint32_t col) const {
  const auto first = row_col_.begin() + row_start_[row], last = row_col_.begin() + row_start_[row + 1];
  return std::binary_search(first, last, col);
}

void DiagonalFlow::add_arcs(std::vector<Arc> arcs) {
  std::vector<Arc> all;
  all.reserve(row_col_.size() + arcs.size());
  for (std::uint32_t i = 0; i < n_; ++i)
    for (std::uint32_t k = row_start_[i]; k < row_start_[i + 1]; ++k) all.push_back({i, row_col_[k], row_cost_[k]});
  std::vector<std::uint32_t> released;
  for (const Arc& arc : arcs)
    if (!has_arc(arc.row, arc.col)) all.push_back(arc), released.push_back(arc.row);
  rebuild_rows(std::move(all));
  std::sort(released.begin(), released.end());
  released.erase(std::unique(released.begin(), released.end()), released.end());
  for (const std::uint32_t i : released) {
    if (mate_a_[i] >= 0) {
      mate_b_[mate_a_[i]] = kNone;
    } else if (mate_a_[i] == kDiagonal) {
      --a_to_diagonal_;
    }
    mate_a_[i] = kNone;
    // No arc enters a_i now; lift its potential until every arc out of it has reduced cost >= 0.
    double p = pi_[hb_] - da_[i];
    for (std::uint32_t k = row_start_[i]; k < row_start_[i + 1]; ++k)
      p = std::max(p, pi_[n_ + row_col_[k]] - row_cost_[k]);
    pi_[i] = p;
    refresh(i);
  }
}

double DiagonalFlow::primal_cost() const {
  double cost = 0;
  for (std::uint32_t i = 0; i < n_; ++i) cost += mate_a_[i] >= 0 ? mate_cost_a_[i] : da_[i];
  for (std::uint32_t j = 0; j < m_; ++j)
    if (mate_b_[j] < 0) cost += db_[j];
  return cost;
}

double DiagonalFlow::dual_without_pairs() const {
  double dual = static_cast<double>(n_) * pi_[hb_] - static_cast<double>(m_) * pi_[ha_];
  for (std::uint32_t i = 0; i < n_; ++i) {
    dual -= pi_[i];
    dual -= std::max(0.0, -(da_[i] + pi_[i] - pi_[hb_]));
  }
  for (std::uint32_t j = 0; j < m_; ++j) {
    dual += pi_[n_ + j];
    dual -= std::max(0.0, -(db_[j] + pi_[ha_] - pi_[n_ + j]));
  }
  // HA -> HB is unbounded: a negative reduced cost there would void the bound. The solver keeps it
  // >= 0 up to rounding; treat anything worse as no bound at all.
  if (pi_[ha_] - pi_[hb_] < -1e-9 * (std::fabs(pi_[ha_]) + std::fabs(pi_[hb_]))) return -kInf;
  return dual;
}

void DiagonalFlow::refresh(std::uint32_t node) {
  double want = std::numeric_limits<double>::quiet_NaN();
  int which = -1;
  if (node < n_) {
    if (mate_a_[node] == kDiagonal) want = -da_[node] - pi_[node], which = 1;
  } else if (node < n_ + m_) {
    if (mate_b_[node - n_] != kDiagonal) want = db_[node - n_] - pi_[node], which = 0;
  }
  auto& set = node < n_ ? hub_b_ : hub_a_;
  if (!std::isnan(key_[node])) {
    if (key_[node] == want) return;
    set.erase({key_[node], node < n_ ? node : node - n_});
  }
  key_[node] = want;
  if (which >= 0) set.insert({want, node < n_ ? node : node - n_});
}

bool DiagonalFlow::is_sink(std::uint32_t v) const {
  if (v >= n_ && v < n_ + m_) return mate_b_[v - n_] == kNone;
  if (v == hb_) return a_to_diagonal_ + flow_hub_ < static_cast<std::int64_t>(n_);
  return false;
}

void DiagonalFlow::relax(std::uint32_t v, double d, std::uint32_t from, double cost) {
  if (final_[v] == run_) return;
  if (seen_[v] == run_ && dist_[v] <= d) return;
  seen_[v] = run_;
  dist_[v] = d;
  pred_[v] = from;
  pred_cost_[v] = cost;
  heap_.push_back({d, v});
  std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
}

void DiagonalFlow::push_generator(int which) {
  const auto& set = which == 0 ? hub_a_ : hub_b_;
  const std::uint32_t offset = which == 0 ? n_ : 0;
  Cursor& c = cursor_[which];
  while (c != set.end() && final_[offset + c->second] == run_) ++c;
  if (c == set.end()) return;
  const std::uint32_t hub = which == 0 ? ha_ : hb_;
  const double d = hub_dist_[which] + std::max(0.0, pi_[hub] + c->first);
  heap_.push_back({d, kGenerator[which]});
  std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
}

void DiagonalFlow::scan(std::uint32_t u, double d) {
  if (u < n_) {
    for (std::uint32_t k = row_start_[u]; k < row_start_[u + 1]; ++k) {
      const std::uint32_t j = row_col_[k];
      if (mate_a_[u] == static_cast<std::int64_t>(j)) continue;
      relax(n_ + j, d + std::max(0.0, row_cost_[k] + pi_[u] - pi_[n_ + j]), u, row_cost_[k]);
    }
    if (mate_a_[u] != kDiagonal) relax(hb_, d + std::max(0.0, da_[u] + pi_[u] - pi_[hb_]), u, da_[u]);
  } else if (u < n_ + m_) {
    const std::int64_t mate = mate_b_[u - n_];
    if (mate >= 0) {
      const auto i = static_cast<std::uint32_t>(mate);
      relax(i, d + std::max(0.0, -mate_cost_a_[i] + pi_[u] - pi_[i]), u, -mate_cost_a_[i]);
    } else if (mate == kDiagonal) {
      relax(ha_, d + std::max(0.0, -db_[u - n_] + pi_[u] - pi_[ha_]), u, -db_[u - n_]);
    }
  } else if (u == ha_) {
    relax(hb_, d + std::max(0.0, pi_[ha_] - pi_[hb_]), u, 0);
    hub_dist_[0] = d;
    cursor_[0] = hub_a_.begin();
    push_generator(0);
  } else {
    if (flow_hub_ > 0) relax(ha_, d + std::max(0.0, pi_[hb_] - pi_[ha_]), u, 0);
    hub_dist_[1] = d;
    cursor_[1] = hub_b_.begin();
    push_generator(1);
  }
}

bool DiagonalFlow::dijkstra(std::uint32_t source) {
  ++run_;
  heap_.clear();
  finalized_.clear();
  seen_[source] = run_;
  dist_[source] = 0;
  heap_.push_back({0.0, source});
  std::int64_t target = -1;
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), std::greater<>());
    const auto [d, id] = heap_.back();
    heap_.pop_back();
    if (id < 0) {
      const int which = id == kGenerator[0] ? 0 : 1;
      const auto& set = which == 0 ? hub_a_ : hub_b_;
      const std::uint32_t offset = which == 0 ? n_ : 0, hub = which == 0 ? ha_ : hb_;
      Cursor& c = cursor_[which];
      while (c != set.end() && final_[offset + c->second] == run_) ++c;
      if (c == set.end()) continue;
      const std::uint32_t v = offset + c->second;
      const double arc_cost = which == 0 ? db_[c->second] : -da_[c->second];
      relax(v, hub_dist_[which] + std::max(0.0, pi_[hub] + c->first), hub, arc_cost);
      ++c;
      push_generator(which);
      continue;
    }
    const auto u = static_cast<std::uint32_t>(id);
    if (final_[u] == run_ || d > dist_[u]) continue;
    final_[u] = run_;
    finalized_.push_back(u);
    if (u != source && is_sink(u)) {
      target = u;
      break;
    }
    scan(u, d);
  }
  if (target < 0) return false;
  const double total = dist_[target];

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
    if (u < n_ && v < n_ + m_) {  // a_i -> b_j
      mate_a_[u] = v - n_, mate_b_[v - n_] = u, mate_cost_a_[u] = pred_cost_[v];
    } else if (u < n_ && v == hb_) {
      mate_a_[u] = kDiagonal, ++a_to_diagonal_;
    } else if (u == ha_ && v < n_ + m_) {
      mate_b_[v - n_] = kDiagonal, ++b_from_diagonal_;
    } else if (u == ha_ && v == hb_) {
      flow_hub_ += amount;
    } else if (u == hb_ && v == ha_) {
      --flow_hub_;
    } else if (u == hb_ && v < n_) {  // a_v leaves the diagonal
      if (mate_a_[v] == kDiagonal) mate_a_[v] = kNone;
      --a_to_diagonal_;
    } else if (v == ha_) {  // b_u no longer fed by the diagonal
      if (mate_b_[u - n_] == kDiagonal) mate_b_[u - n_] = kNone;
      --b_from_diagonal_;
    } else {  // b_u -> a_v: the pair (a_v, b_u) is undone
      if (mate_a_[v] == static_cast<std::int64_t>(u - n_)) mate_a_[v] = kNone;
      if (mate_b_[u - n_] == static_cast<std::int64_t>(v)) mate_b_[u - n_] = kNone;
    }
  }
  for (const std::uint32_t v : finalized_) pi_[v] -= total - dist_[v];
  for (const std::uint32_t v : finalized_) refresh(v);
  for (const std::uint32_t v : path) refresh(v);
  ++augmentations_;
  return true;
}

void DiagonalFlow::solve() {
  for (std::uint32_t i = 0; i < n_; ++i)
    if (mate_a_[i] == kNone && !dijkstra(i)) throw std::logic_error("diagonal flow: no augmenting path");
  while (static_cast<std::int64_t>(m_) - b_from_diagonal_ - flow_hub_ > 0)
    if (!dijkstra(ha_)) throw std::logic_error("diagonal flow: no augmenting path from the diagonal");
}

}  // namespace fnet
