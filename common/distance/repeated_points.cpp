#include "common/distance/repeated_points.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

#include "common/distance/linf_kdtree.hpp"
#include "common/distance/network_simplex.hpp"

namespace fnet {

namespace {

// The flow between distinct points as a matching of the input's points: each pair flow of amount
// k pairs k copies of its two points, and the copies no flow took go to the diagonal.
void split_among_copies(const DistinctPoints& a, const DistinctPoints& b,
                        std::span<const NetworkSimplex::PairFlow> flows, MatchingBuilder& builder) {
  std::vector<std::uint32_t> next_a(a.first.begin(), a.first.end() - 1), next_b(b.first.begin(), b.first.end() - 1);
  for (const auto& f : flows)
    for (std::uint32_t k = 0; k < f.amount; ++k) builder.pair(a.members[next_a[f.i]++], b.members[next_b[f.j]++]);
  for (std::uint32_t i = 0; i < a.points.size(); ++i)
    while (next_a[i] < a.first[i + 1]) builder.a_to_diagonal(a.members[next_a[i]++]);
  for (std::uint32_t j = 0; j < b.points.size(); ++j)
    while (next_b[j] < b.first[j + 1]) builder.b_to_diagonal(b.members[next_b[j]++]);
}

bool solve_distinct(std::size_t distinct_a, std::size_t distinct_b, std::size_t points_a, std::size_t points_b) {
  return 2 * (distinct_a + distinct_b) <= points_a + points_b && distinct_a * distinct_b <= kMaxDistinctArcs;
}

}  // namespace

DistinctPoints distinct_points(std::span<const PlanePoint> points) {
  DistinctPoints out;
  out.members.resize(points.size());
  std::iota(out.members.begin(), out.members.end(), 0u);
  std::sort(out.members.begin(), out.members.end(), [&](std::uint32_t p, std::uint32_t r) {
    const PlanePoint u = points[p], v = points[r];
    return u.x != v.x ? u.x < v.x : u.y != v.y ? u.y < v.y : p < r;
  });
  for (std::size_t k = 0; k < out.members.size(); ++k) {
    const PlanePoint p = points[out.members[k]];
    if (out.points.empty() || !(p.x == out.points.back().x && p.y == out.points.back().y)) {
      out.points.push_back(p);
      out.first.push_back(static_cast<std::uint32_t>(k));
      out.count.push_back(0);
    }
    ++out.count.back();
  }
  out.first.push_back(static_cast<std::uint32_t>(out.members.size()));
  return out;
}

std::size_t count_distinct(std::span<const PlanePoint> points) {
  // Open addressing over a power of two at least twice the points; slots hold index + 1.
  std::size_t size = 16;
  while (size < 2 * points.size()) size *= 2;
  std::vector<std::uint32_t> slot(size, 0);
  std::size_t distinct = 0;
  for (std::uint32_t k = 0; k < points.size(); ++k) {
    const PlanePoint p = points[k];
    // + 0.0 makes -0 and +0 (equal points) hash alike.
    std::uint64_t h = std::bit_cast<std::uint64_t>(p.x + 0.0) * 0x9e3779b97f4a7c15ull ^
                      std::bit_cast<std::uint64_t>(p.y + 0.0) * 0xc2b2ae3d27d4eb4full;
    h ^= h >> 29;
    for (std::size_t s = h & (size - 1);; s = (s + 1) & (size - 1)) {
      if (slot[s] == 0) {
        slot[s] = k + 1;
        ++distinct;
        break;
      }
      const PlanePoint q = points[slot[s] - 1];
      if (q.x == p.x && q.y == p.y) break;
    }
  }
  return distinct;
}

bool solve_distinct(std::span<const PlanePoint> a, std::span<const PlanePoint> b) {
  if (a.empty() || b.empty()) return false;
  return solve_distinct(count_distinct(a), count_distinct(b), a.size(), b.size());
}

DistinctTransport distinct_transport(const DistinctPoints& a, const DistinctPoints& b, const ArcPower& power,
                                     MatchingBuilder* builder) {
  const auto n = static_cast<std::uint32_t>(a.points.size()), m = static_cast<std::uint32_t>(b.points.size());
  std::vector<double> da(n), db(m);
  for (std::uint32_t i = 0; i < n; ++i) da[i] = power(std::fabs(a.points[i].x - a.points[i].y) / 2);
  for (std::uint32_t j = 0; j < m; ++j) db[j] = power(std::fabs(b.points[j].x - b.points[j].y) / 2);
  const auto cost = [&](std::uint32_t i, std::uint32_t j) { return power(linf_distance(a.points[i], b.points[j])); };

  NetworkSimplex simplex(da, db, a.count, b.count);
  DistinctTransport out;
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = 0; j < m; ++j)
      if (const double c = cost(i, j); c < da[i] + db[j]) {
        simplex.add_pair_arc(i, j, c);
        ++out.pair_arcs;
      }
  simplex.price_by_blocks();  // a complete graph: dense
  simplex.solve();
  out.pivots = simplex.pivots();

  // The flow's cost: the pairs, then what each point leaves to the diagonal.
  std::vector<std::uint32_t> left_a = a.count, left_b = b.count;
  const std::vector<NetworkSimplex::PairFlow> flows = simplex.pair_flows();
  for (const auto& f : flows) {
    out.cost += f.amount * cost(f.i, f.j);
    left_a[f.i] -= f.amount;
    left_b[f.j] -= f.amount;
  }
  for (std::uint32_t i = 0; i < n; ++i) out.cost += left_a[i] * da[i];
  for (std::uint32_t j = 0; j < m; ++j) out.cost += left_b[j] * db[j];

  // A feasible dual from the potentials (reduced cost c(u, v) + pi(u) - pi(v) >= 0 on every arc):
  // pi(HB) = 0; pi(a_i) raised to -da_i where below; pi(HA) raised to 0; each pi(b_j) then the least
  // of pi(HA) + db_j and pi(a_i) + c_ij over every i (pairs that do not beat the diagonal included:
  // the bound holds over the complete graph). Weak duality: cost >= -sum over nodes of pi * supply.
  const auto pi = simplex.potentials();
  std::vector<double> pa(n);
  for (std::uint32_t i = 0; i < n; ++i) pa[i] = std::max(pi[i], -da[i]);
  const double ha = std::max(pi[n + m], 0.0);
  double dual = -ha * std::accumulate(b.count.begin(), b.count.end(), 0.0);
  for (std::uint32_t i = 0; i < n; ++i) dual -= pa[i] * a.count[i];
  for (std::uint32_t j = 0; j < m; ++j) {
    double pb = ha + db[j];
    for (std::uint32_t i = 0; i < n; ++i) pb = std::min(pb, pa[i] + cost(i, j));
    dual += pb * b.count[j];
  }
  out.dual = dual;

  if (builder) split_among_copies(a, b, flows, *builder);
  return out;
}

namespace {

// Dinic's maximum flow on a small dense graph; capacities are counts.
class MaxFlow {
 public:
  explicit MaxFlow(std::uint32_t nodes) : head_(nodes, -1), level_(nodes), cursor_(nodes) {}
  std::uint32_t add(std::uint32_t from, std::uint32_t to, std::int64_t capacity) {
    const auto e = static_cast<std::uint32_t>(edges_.size());
    edges_.push_back({to, head_[from], capacity});
    head_[from] = static_cast<std::int32_t>(e);
    edges_.push_back({from, head_[to], 0});
    head_[to] = static_cast<std::int32_t>(e + 1);
    return e;
  }
  std::int64_t flow_on(std::uint32_t e) const { return edges_[e ^ 1].capacity; }
  std::int64_t run(std::uint32_t s, std::uint32_t t) {
    std::int64_t total = 0;
    while (levels(s, t)) {
      std::copy(head_.begin(), head_.end(), cursor_.begin());
      while (const std::int64_t pushed = push(s, t, std::numeric_limits<std::int64_t>::max())) total += pushed;
    }
    return total;
  }

 private:
  struct Edge {
    std::uint32_t to;
    std::int32_t next;
    std::int64_t capacity;  // residual
  };
  bool levels(std::uint32_t s, std::uint32_t t) {
    std::fill(level_.begin(), level_.end(), -1);
    std::vector<std::uint32_t> queue{s};
    level_[s] = 0;
    for (std::size_t k = 0; k < queue.size(); ++k)
      for (std::int32_t e = head_[queue[k]]; e >= 0; e = edges_[e].next)
        if (edges_[e].capacity > 0 && level_[edges_[e].to] < 0) {
          level_[edges_[e].to] = level_[queue[k]] + 1;
          queue.push_back(edges_[e].to);
        }
    return level_[t] >= 0;
  }
  std::int64_t push(std::uint32_t v, std::uint32_t t, std::int64_t limit) {
    if (v == t) return limit;
    for (std::int32_t& e = cursor_[v]; e >= 0; e = edges_[e].next) {
      Edge& edge = edges_[e];
      if (edge.capacity <= 0 || level_[edge.to] != level_[v] + 1) continue;
      if (const std::int64_t pushed = push(edge.to, t, std::min(limit, edge.capacity))) {
        edge.capacity -= pushed;
        edges_[e ^ 1].capacity += pushed;
        return pushed;
      }
    }
    return 0;
  }
  std::vector<Edge> edges_;
  std::vector<std::int32_t> head_, level_, cursor_;
};

}  // namespace

DistinctBottleneck distinct_bottleneck(const DistinctPoints& a, const DistinctPoints& b, MatchingBuilder* builder) {
  const auto n = static_cast<std::uint32_t>(a.points.size()), m = static_cast<std::uint32_t>(b.points.size());
  std::vector<double> da(n), db(m);
  for (std::uint32_t i = 0; i < n; ++i) da[i] = std::fabs(a.points[i].x - a.points[i].y) / 2;
  for (std::uint32_t j = 0; j < m; ++j) db[j] = std::fabs(b.points[j].x - b.points[j].y) / 2;
  // A pair longer than both points' diagonal distances is never needed: both to the diagonal
  // instead costs no more.
  struct Pair {
    std::uint32_t i, j;
    double length;
  };
  std::vector<Pair> pairs;
  std::vector<double> candidates(da.begin(), da.end());
  candidates.insert(candidates.end(), db.begin(), db.end());
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = 0; j < m; ++j)
      if (const double d = linf_distance(a.points[i], b.points[j]); d < std::max(da[i], db[j])) {
        pairs.push_back({i, j, d});
        candidates.push_back(d);
      }
  candidates.push_back(0);
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());

  const std::int64_t total_a = std::accumulate(a.count.begin(), a.count.end(), std::int64_t{0}),
                     total_b = std::accumulate(b.count.begin(), b.count.end(), std::int64_t{0});
  // Nodes: source, a_0.., HA, b_0.., HB, sink. Whether every copy is matched within r; flows
  // (optional) receives the pair flows of the matching found.
  const std::uint32_t source = 0, ha = n + 1, hb = n + m + 2, sink = n + m + 3;
  const auto decide = [&](double r, std::vector<NetworkSimplex::PairFlow>* flows) {
    MaxFlow flow(n + m + 4);
    for (std::uint32_t i = 0; i < n; ++i) {
      flow.add(source, 1 + i, a.count[i]);
      if (da[i] <= r) flow.add(1 + i, hb, total_a);
    }
    flow.add(source, ha, total_b);
    flow.add(ha, hb, total_b);
    for (std::uint32_t j = 0; j < m; ++j) {
      flow.add(n + 2 + j, sink, b.count[j]);
      if (db[j] <= r) flow.add(ha, n + 2 + j, b.count[j]);
    }
    flow.add(hb, sink, total_a);
    std::vector<std::pair<const Pair*, std::uint32_t>> pair_edges;  // each pair within r, its edge
    for (const Pair& p : pairs)
      if (p.length <= r) pair_edges.push_back({&p, flow.add(1 + p.i, n + 2 + p.j, total_a)});
    const bool feasible = flow.run(source, sink) == total_a + total_b;
    if (flows)
      for (const auto& [p, e] : pair_edges)
        if (const std::int64_t amount = flow.flow_on(e); amount > 0)
          flows->push_back({p->i, p->j, static_cast<std::uint32_t>(amount)});
    return feasible;
  };
  // candidates.back() (every point to the diagonal) is feasible; find the least feasible.
  DistinctBottleneck result;
  std::size_t lo = 0, hi = candidates.size() - 1;  // hi feasible; below lo none is
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    ++result.flows;
    if (decide(candidates[mid], nullptr))
      hi = mid;
    else
      lo = mid + 1;
  }
  result.value = candidates[hi];
  if (builder) {
    ++result.flows;
    std::vector<NetworkSimplex::PairFlow> flows;
    decide(result.value, &flows);
    split_among_copies(a, b, flows, *builder);
  }
  return result;
}

}  // namespace fnet
