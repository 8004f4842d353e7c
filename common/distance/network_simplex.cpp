#include "common/distance/network_simplex.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/distance/work_deadline.hpp"

namespace fnet {

NetworkSimplex::NetworkSimplex(std::span<const double> da, std::span<const double> db)
    : NetworkSimplex(da, db, {}, {}) {}

NetworkSimplex::NetworkSimplex(std::span<const double> da, std::span<const double> db,
                               std::span<const std::uint32_t> count_a, std::span<const std::uint32_t> count_b)
    : n_(static_cast<std::uint32_t>(da.size())), m_(static_cast<std::uint32_t>(db.size())), root_(n_ + m_ + 1) {
  const std::uint32_t nodes = n_ + m_ + 2, ha = n_ + m_, hb = root_;
  if ((!count_a.empty() && count_a.size() != n_) || (!count_b.empty() && count_b.size() != m_))
    throw std::invalid_argument("NetworkSimplex: one count per point");
  const auto count = [](std::span<const std::uint32_t> counts, std::uint32_t k) -> std::int64_t {
    if (counts.empty()) return 1;
    if (counts[k] == 0) throw std::invalid_argument("NetworkSimplex: a point's count is 0");
    return counts[k];
  };
  supply_.assign(nodes, 0);
  for (std::uint32_t i = 0; i < n_; ++i) supply_[i] = count(count_a, i), supply_[root_] -= supply_[i];
  for (std::uint32_t j = 0; j < m_; ++j) supply_[n_ + j] = -count(count_b, j), supply_[ha] -= supply_[n_ + j];
  if (supply_[ha] > std::numeric_limits<std::int32_t>::max() ||
      -supply_[root_] > std::numeric_limits<std::int32_t>::max())
    throw std::invalid_argument("NetworkSimplex: more than 2^31 - 1 points on a side");
  arcs_.reserve(n_ + m_ + 1);
  for (std::uint32_t i = 0; i < n_; ++i) arcs_.push_back({i, hb, da[i]});
  for (std::uint32_t j = 0; j < m_; ++j) arcs_.push_back({ha, n_ + j, db[j]});
  arcs_.push_back({ha, hb, 0.0});
  first_pair_arc_ = arcs_.size();
  flow_.resize(arcs_.size());
  for (std::uint32_t i = 0; i < n_; ++i) flow_[i] = static_cast<std::int32_t>(supply_[i]);
  for (std::uint32_t j = 0; j < m_; ++j) flow_[n_ + j] = static_cast<std::int32_t>(-supply_[n_ + j]);
  flow_.back() = 0;
  in_tree_.assign(arcs_.size(), 1);

  parent_.assign(nodes, static_cast<std::int32_t>(hb));
  pred_.resize(nodes);
  up_.assign(nodes, 1);
  thread_.resize(nodes);
  rev_thread_.resize(nodes);
  size_.assign(nodes, 1);
  pi_.assign(nodes, 0.0);
  // Preorder from HB: HB, a_0 .. a_{n-1}, HA, b_0 .. b_{m-1}.
  std::vector<std::uint32_t> order;
  order.reserve(nodes);
  order.push_back(hb);
  for (std::uint32_t i = 0; i < n_; ++i) {
    order.push_back(i);
    pred_[i] = i;
    pi_[i] = -da[i];  // da_i + pi(a_i) - pi(HB) == 0
  }
  order.push_back(ha);
  pred_[ha] = n_ + m_;
  for (std::uint32_t j = 0; j < m_; ++j) {
    const std::uint32_t v = n_ + j;
    order.push_back(v);
    parent_[v] = static_cast<std::int32_t>(ha);
    pred_[v] = n_ + j;
    up_[v] = 0;
    pi_[v] = db[j];  // db_j + pi(HA) - pi(b_j) == 0
  }
  parent_[hb] = -1;
  pred_[hb] = 0;
  up_[hb] = 0;
  size_[ha] = m_ + 1;
  size_[hb] = nodes;
  link_thread(order);
  position_.assign(nodes, 0);
}

NetworkSimplex::NetworkSimplex(std::span<const double> da, std::span<const double> db, std::span<const PairStart> pairs)
    : NetworkSimplex(da, db) {
  const std::uint32_t ha = n_ + m_, hb = root_;
  std::vector<std::int64_t> mate(n_, -1);
  for (const PairStart& p : pairs) {
    mate[p.i] = p.j;
    const std::uint32_t v = n_ + p.j, e = static_cast<std::uint32_t>(arcs_.size());
    add_pair_arc(p.i, p.j, p.cost);
    flow_[e] = 1;
    in_tree_[e] = 1;
    flow_[p.i] = 0;       // a_i -> HB, still the tree arc of a_i
    flow_[n_ + p.j] = 0;  // HA -> b_j leaves the tree
    in_tree_[n_ + p.j] = 0;
    parent_[v] = static_cast<std::int32_t>(p.i);
    pred_[v] = e;
    up_[v] = 0;
    size_[p.i] = 2;
    --size_[ha];
  }
  flow_[first_pair_arc_ - 1] = static_cast<std::int32_t>(pairs.size());  // HA -> HB
  std::vector<std::uint32_t> order;
  order.reserve(node_count());
  order.push_back(hb);
  for (std::uint32_t i = 0; i < n_; ++i) {
    order.push_back(i);
    if (mate[i] >= 0) order.push_back(n_ + static_cast<std::uint32_t>(mate[i]));
  }
  order.push_back(ha);
  for (std::uint32_t j = 0; j < m_; ++j)
    if (parent_[n_ + j] == static_cast<std::int32_t>(ha)) order.push_back(n_ + j);
  link_thread(order);
  recompute_potentials();
}

void NetworkSimplex::link_thread(std::span<const std::uint32_t> order) {
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::uint32_t next = order[(k + 1) % order.size()];
    thread_[order[k]] = next;
    rev_thread_[next] = order[k];
  }
}

void NetworkSimplex::add_pair_arc(std::uint32_t i, std::uint32_t j, double cost) {
  arcs_.push_back({i, n_ + j, cost});
  flow_.push_back(0);
  in_tree_.push_back(0);
}

bool NetworkSimplex::improving(std::uint32_t e) const {
  if (in_tree_[e]) return false;
  // Improving beyond rounding, which is relative to the terms (costs may be 1e-24 of others).
  const Arc& arc = arcs_[e];
  const double pu = pi_[arc.from], pv = pi_[arc.to];
  const double rc = arc.cost + pu - pv;
  return rc < 0 && rc < -kRelativeTolerance * (arc.cost + std::fabs(pu) + std::fabs(pv));
}

void NetworkSimplex::build_incidence() {
  // Per node a_i or b_j, the arcs with an end there (HA's and HB's are never listed).
  const std::uint32_t points = n_ + m_;
  incidence_start_.assign(points + 1, 0);
  for (const Arc& arc : arcs_) {
    if (arc.from < points) ++incidence_start_[arc.from + 1];
    if (arc.to < points) ++incidence_start_[arc.to + 1];
  }
  for (std::uint32_t v = 0; v < points; ++v) incidence_start_[v + 1] += incidence_start_[v];
  incidence_.resize(incidence_start_[points]);
  std::vector<std::uint32_t> fill(incidence_start_.begin(), incidence_start_.end() - 1);
  for (std::uint32_t e = 0; e < arcs_.size(); ++e) {
    if (arcs_[e].from < points) incidence_[fill[arcs_[e].from]++] = e;
    if (arcs_[e].to < points) incidence_[fill[arcs_[e].to]++] = e;
  }
  in_pool_.assign(arcs_.size(), 0);
}

void NetworkSimplex::rebuild_pool() {
  for (const std::uint32_t e : pool_) in_pool_[e] = 0;
  pool_.clear();
  for (std::uint32_t e = 0; e < arcs_.size(); ++e)
    if (improving(e)) pool_.push_back(e), in_pool_[e] = 1;
  scanned_total_ += arcs_.size();
  ++rebuilds_;
  next_in_pool_ = 0;
}

std::int64_t NetworkSimplex::find_entering() {
  // Block search over the pool: from the cursor, the most negative reduced cost among the first
  // `block` entries still improving; entries no longer improving leave the pool.
  const std::size_t block =
      std::max<std::size_t>(16, static_cast<std::size_t>(kBlockFactor * std::sqrt(static_cast<double>(arcs_.size()))));
  double best = 0;
  std::int64_t best_arc = -1;
  std::size_t looked = 0;
  while (!pool_.empty()) {
    if (next_in_pool_ >= pool_.size()) {
      next_in_pool_ = 0;
      if (best_arc >= 0) break;
    }
    const std::uint32_t e = pool_[next_in_pool_];
    ++scanned_total_;
    if (!improving(e)) {
      in_pool_[e] = 0;
      pool_[next_in_pool_] = pool_.back();
      pool_.pop_back();
      continue;
    }
    const double rc = reduced_cost(e);
    if (rc < best) best = rc, best_arc = e;
    ++next_in_pool_;
    if (++looked >= block && best_arc >= 0) break;
  }
  return best_arc;
}

std::int64_t NetworkSimplex::find_entering_by_blocks() {
  const std::size_t count = arcs_.size();
  const std::size_t block = std::max<std::size_t>(16, static_cast<std::size_t>(std::sqrt(static_cast<double>(count))));
  double best = 0;
  std::int64_t best_arc = -1;
  std::size_t looked = 0;
  while (looked < count) {
    const auto e = static_cast<std::uint32_t>(next_arc_);
    next_arc_ = next_arc_ + 1 == count ? 0 : next_arc_ + 1;
    if (improving(e)) {
      const double rc = reduced_cost(e);
      if (rc < best) best = rc, best_arc = e;
    }
    if (++looked % block == 0 && best_arc >= 0) break;
  }
  scanned_total_ += looked;
  return best_arc;
}

void NetworkSimplex::refresh_pool() {
  // Only arcs with exactly one end in the moved subtree changed their reduced cost
  // cost + pi(from) - pi(to), by +-sigma: raised potentials (sigma > 0) lower it on arcs into the
  // subtree, lowered ones on arcs out of it. Arcs into a node end at some b_j (from a_i or HA),
  // arcs out of one start at some a_i or at HA; so only the moved b_j's arcs, or only the moved
  // a_i's (and HA's), can have become improving. A subtree too big to list: scan everything.
  const std::uint32_t points = n_ + m_, ha = n_ + m_;
  const bool raised = last_sigma_ > 0;
  std::size_t work = 0;
  bool hub = false;  // HA moved with potentials lowered: its arcs HA -> b_j and HA -> HB
  for (const std::uint32_t v : moved_) {
    if (v == ha) {
      hub = !raised;
      if (hub) work += m_ + 1;
    } else if (v < points && (v >= n_) == raised) {
      work += incidence_start_[v + 1] - incidence_start_[v];
    }
  }
  if (work * 2 > arcs_.size()) return rebuild_pool();
  const auto look = [&](std::uint32_t e) {
    if (!in_pool_[e] && improving(e)) pool_.push_back(e), in_pool_[e] = 1;
  };
  if (hub)
    for (std::uint32_t e = n_; e < first_pair_arc_; ++e) look(e);
  for (const std::uint32_t v : moved_)
    if (v < points && (v >= n_) == raised)
      for (std::uint32_t k = incidence_start_[v]; k < incidence_start_[v + 1]; ++k) look(incidence_[k]);
  scanned_total_ += work;
}

void NetworkSimplex::pivot(std::uint32_t entering) {
  const Arc arc = arcs_[entering];
  const std::uint32_t p = arc.from, q = arc.to;  // the flow goes p -> q on the entering arc
  std::uint32_t u = p, v = q;
  while (u != v) {  // the apex: an ancestor has the larger subtree
    if (size_[u] < size_[v])
      u = static_cast<std::uint32_t>(parent_[u]);
    else
      v = static_cast<std::uint32_t>(parent_[v]);
  }
  const std::uint32_t join = u;
  // Around the cycle from the apex: down to p (flow parent -> child), p -> q, up from q to the apex
  // (flow child -> parent). Blocking arcs are those whose flow falls; the last one met wins ties
  // (strict on p's side, walked from p upwards; non-strict on q's side), which keeps the tree
  // strongly feasible.
  std::int32_t delta = std::numeric_limits<std::int32_t>::max();
  std::int64_t u_out = -1;
  bool on_q_side = false;
  for (std::uint32_t w = p; w != join; w = static_cast<std::uint32_t>(parent_[w]))
    if (up_[w] && flow_[pred_[w]] < delta) delta = flow_[pred_[w]], u_out = w;
  for (std::uint32_t w = q; w != join; w = static_cast<std::uint32_t>(parent_[w]))
    if (!up_[w] && flow_[pred_[w]] <= delta) delta = flow_[pred_[w]], u_out = w, on_q_side = true;
  if (u_out < 0) throw std::logic_error("network simplex: a cycle without a blocking arc");
  ++pivots_;
  if (delta > 0) {
    flow_[entering] += delta;
    for (std::uint32_t w = p; w != join; w = static_cast<std::uint32_t>(parent_[w]))
      flow_[pred_[w]] += up_[w] ? -delta : delta;
    for (std::uint32_t w = q; w != join; w = static_cast<std::uint32_t>(parent_[w]))
      flow_[pred_[w]] += up_[w] ? delta : -delta;
  } else {
    ++degenerate_;
  }
  const std::uint32_t leaving = pred_[static_cast<std::uint32_t>(u_out)];
  in_tree_[leaving] = 0;
  in_tree_[entering] = 1;
  // The side of the leaving arc moves: it hangs from the other end of the entering arc.
  const std::uint32_t u_in = on_q_side ? q : p, v_in = on_q_side ? p : q;
  const double rc = reduced_cost(entering);
  move_subtree(static_cast<std::uint32_t>(u_out), u_in, v_in, entering, join, u_in == p ? -rc : rc);
}

void NetworkSimplex::move_subtree(std::uint32_t u_out, std::uint32_t u_in, std::uint32_t v_in, std::uint32_t entering,
                                  std::uint32_t join, double sigma) {
  const std::uint32_t size = size_[u_out];
  const std::uint32_t v_out = static_cast<std::uint32_t>(parent_[u_out]);
  // The subtree in its old preorder (contiguous in the thread), cut out of the thread.
  moved_.resize(size);
  std::uint32_t w = u_out;
  for (std::uint32_t k = 0; k < size; ++k) {
    moved_[k] = w;
    position_[w] = k;
    w = thread_[w];
  }
  const std::uint32_t before = rev_thread_[u_out];
  thread_[before] = w;
  rev_thread_[w] = before;
  // The stem u_in = s_0, s_1, ..., s_k = u_out. Re-rooted at s_0, the preorder is s_0's old segment,
  // then for t >= 1 s_t's old segment without s_{t-1}'s (s_t, then its other children's subtrees).
  stem_.clear();
  for (w = u_in; w != u_out; w = static_cast<std::uint32_t>(parent_[w])) stem_.push_back(w);
  stem_.push_back(u_out);
  order_.clear();
  {
    const std::uint32_t s0 = stem_[0];
    order_.insert(order_.end(), moved_.begin() + position_[s0], moved_.begin() + position_[s0] + size_[s0]);
  }
  for (std::size_t t = 1; t < stem_.size(); ++t) {
    const std::uint32_t s = stem_[t], c = stem_[t - 1];
    order_.insert(order_.end(), moved_.begin() + position_[s], moved_.begin() + position_[c]);
    order_.insert(order_.end(), moved_.begin() + position_[c] + size_[c], moved_.begin() + position_[s] + size_[s]);
  }
  // Parents, tree arcs and sizes along the stem, from u_out down (each reads its child's old values).
  for (std::size_t t = stem_.size() - 1; t >= 1; --t) {
    const std::uint32_t s = stem_[t], c = stem_[t - 1];
    parent_[s] = static_cast<std::int32_t>(c);
    pred_[s] = pred_[c];
    up_[s] = up_[c] ? 0 : 1;
    size_[s] = size - size_[c];
  }
  parent_[u_in] = static_cast<std::int32_t>(v_in);
  pred_[u_in] = entering;
  up_[u_in] = arcs_[entering].from == u_in ? 1 : 0;
  size_[u_in] = size;
  last_sigma_ = sigma;
  // Back into the thread right after v_in.
  const std::uint32_t after = thread_[v_in];
  std::uint32_t last = v_in;
  for (const std::uint32_t x : order_) {
    thread_[last] = x;
    rev_thread_[x] = last;
    last = x;
    pi_[x] += sigma;
  }
  thread_[last] = after;
  rev_thread_[after] = last;
  // Sizes on the two paths to the apex.
  for (w = v_out; w != join; w = static_cast<std::uint32_t>(parent_[w])) size_[w] -= size;
  for (w = v_in; w != join; w = static_cast<std::uint32_t>(parent_[w])) size_[w] += size;
}

void NetworkSimplex::recompute_potentials() {
  pi_[root_] = 0;
  for (std::uint32_t w = thread_[root_]; w != root_; w = thread_[w]) {
    const Arc& arc = arcs_[pred_[w]];
    const double parent_pi = pi_[static_cast<std::uint32_t>(parent_[w])];
    pi_[w] = up_[w] ? parent_pi - arc.cost : parent_pi + arc.cost;
  }
}

void NetworkSimplex::solve() {
  // Pivot, then drop the pivots' rounding and look again; a pass after the recomputation that
  // finds nothing ends it. Three passes at most: after that what is left is rounding.
  if (!by_blocks_) build_incidence();
  for (int pass = 0; pass < 3; ++pass) {
    const std::size_t before = pivots_;
    if (by_blocks_) {
      for (std::int64_t e; (e = find_entering_by_blocks()) >= 0;) {
        check_work_deadline();
        pivot(static_cast<std::uint32_t>(e));
      }
      recompute_potentials();
      if (pivots_ == before) break;
      continue;
    }
    rebuild_pool();
    for (;;) {
      std::int64_t e = find_entering();
      if (e < 0) {
        // The pool holds every improving arc (it is complete after each refresh); the scan only
        // guards against what rounding may have hidden.
        rebuild_pool();
        e = find_entering();
        if (e < 0) break;
      }
      check_work_deadline();
      pivot(static_cast<std::uint32_t>(e));
      refresh_pool();
    }
    recompute_potentials();
    if (pivots_ == before) break;
  }
}

std::vector<NetworkSimplex::PairFlow> NetworkSimplex::pair_flows() const {
  std::vector<PairFlow> out;
  for (std::size_t e = first_pair_arc_; e < arcs_.size(); ++e)
    if (flow_[e] > 0) out.push_back({arcs_[e].from, arcs_[e].to - n_, static_cast<std::uint32_t>(flow_[e])});
  return out;
}

std::vector<std::int64_t> NetworkSimplex::mates_of_a() const {
  std::vector<std::int64_t> mate(n_, -1);
  for (std::size_t e = first_pair_arc_; e < arcs_.size(); ++e)
    if (flow_[e] > 0) mate[arcs_[e].from] = static_cast<std::int64_t>(arcs_[e].to) - n_;
  return mate;
}

bool NetworkSimplex::consistent() const {
  const std::uint32_t nodes = node_count();
  // The thread visits every node once, parents before children, each subtree contiguous.
  std::vector<std::uint32_t> seen_at(nodes, nodes);
  std::uint32_t w = root_;
  for (std::uint32_t k = 0; k < nodes; ++k) {
    if (seen_at[w] != nodes) return false;
    seen_at[w] = k;
    if (rev_thread_[thread_[w]] != w) return false;
    w = thread_[w];
  }
  if (w != root_) return false;
  std::vector<std::uint32_t> sizes(nodes, 1);
  std::vector<std::int64_t> balance = supply_;
  std::size_t tree_arcs = 0;
  for (std::size_t e = 0; e < arcs_.size(); ++e) {
    if (flow_[e] < 0) return false;
    if (!in_tree_[e] && flow_[e] != 0) return false;
    tree_arcs += in_tree_[e];
    balance[arcs_[e].from] -= flow_[e];
    balance[arcs_[e].to] += flow_[e];
    if (in_tree_[e] && std::fabs(reduced_cost(static_cast<std::uint32_t>(e))) > 1e-9 * (1 + std::fabs(arcs_[e].cost)))
      return false;
  }
  if (tree_arcs != nodes - 1) return false;
  for (std::uint32_t v = 0; v < nodes; ++v)
    if (balance[v] != 0) return false;
  for (std::uint32_t v = 0; v < nodes; ++v) {
    if (v == root_) continue;
    const auto p = static_cast<std::uint32_t>(parent_[v]);
    if (seen_at[p] >= seen_at[v]) return false;
    const Arc& arc = arcs_[pred_[v]];
    if (!in_tree_[pred_[v]]) return false;
    if (up_[v] ? (arc.from != v || arc.to != p) : (arc.from != p || arc.to != v)) return false;
  }
  // Sizes: children after parents in the thread, so accumulate backwards.
  std::vector<std::uint32_t> by_position(nodes);
  for (std::uint32_t v = 0; v < nodes; ++v) by_position[seen_at[v]] = v;
  for (std::uint32_t k = nodes; k-- > 1;)
    sizes[static_cast<std::uint32_t>(parent_[by_position[k]])] += sizes[by_position[k]];
  for (std::uint32_t v = 0; v < nodes; ++v) {
    if (sizes[v] != size_[v]) return false;
    // Contiguity: the subtree occupies positions [seen_at[v], seen_at[v] + size).
    if (v != root_) {
      const auto p = static_cast<std::uint32_t>(parent_[v]);
      if (seen_at[v] + size_[v] > seen_at[p] + size_[p]) return false;
    }
  }
  return true;
}

}  // namespace fnet
