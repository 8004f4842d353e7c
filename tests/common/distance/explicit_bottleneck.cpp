#include "explicit_bottleneck.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>

#include "tests/common/distance/distance_support.hpp"

namespace fnet::test {
namespace {

double diagonal(PlanePoint p) { return std::fabs(p.x - p.y) / 2; }

// Calls f(i, j, d) for every pair a_i, b_j at distance d <= r.
void pairs_within(const std::vector<PlanePoint>& a, const std::vector<PlanePoint>& b, double r,
                  const std::function<void(std::size_t, std::size_t, double)>& f) {
  std::vector<std::size_t> by_x(b.size());
  std::iota(by_x.begin(), by_x.end(), std::size_t{0});
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t p, std::size_t q) { return b[p].x < b[q].x; });
  // A window a little wider than r in birth: the exact test below decides.
  const double reach = r * (1 + 1e-9) + 1e-300;
  for (std::size_t i = 0; i < a.size(); ++i) {
    auto k =
        std::lower_bound(by_x.begin(), by_x.end(), a[i].x - reach, [&](std::size_t j, double x) { return b[j].x < x; });
    for (; k != by_x.end() && b[*k].x <= a[i].x + reach; ++k)
      if (const double d = linf(a[i], b[*k]); d <= r) f(i, *k, d);
  }
}

// The size of a maximum matching of a bipartite graph (left vertices 0..adj.size()-1).
std::size_t hopcroft_karp(const std::vector<std::vector<std::uint32_t>>& adj, std::size_t right) {
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> mate_l(adj.size(), kNone), mate_r(right, kNone), dist(adj.size());
  std::size_t size = 0;
  for (std::uint32_t u = 0; u < adj.size(); ++u)  // a greedy start spares most phases
    for (const std::uint32_t v : adj[u])
      if (mate_r[v] == kNone) {
        mate_l[u] = v, mate_r[v] = u, ++size;
        break;
      }
  for (;;) {
    // Layers from the free left vertices; `found` is the length of the shortest augmenting path.
    std::vector<std::uint32_t> queue;
    for (std::uint32_t u = 0; u < adj.size(); ++u) {
      dist[u] = mate_l[u] == kNone ? 0 : kNone;
      if (mate_l[u] == kNone) queue.push_back(u);
    }
    std::uint32_t found = kNone;
    for (std::size_t h = 0; h < queue.size(); ++h) {
      const std::uint32_t u = queue[h];
      if (dist[u] >= found) continue;
      for (const std::uint32_t v : adj[u]) {
        const std::uint32_t w = mate_r[v];
        if (w == kNone) {
          found = std::min(found, dist[u] + 1);
        } else if (dist[w] == kNone) {
          dist[w] = dist[u] + 1;
          queue.push_back(w);
        }
      }
    }
    if (found == kNone) return size;
    // Vertex-disjoint shortest paths, depth first without recursion.
    std::vector<std::size_t> next(adj.size(), 0);
    for (std::uint32_t root = 0; root < adj.size(); ++root) {
      if (mate_l[root] != kNone) continue;
      std::vector<std::uint32_t> path{root};
      while (!path.empty()) {
        const std::uint32_t u = path.back();
        if (next[u] == adj[u].size()) {
          dist[u] = kNone;  // dead for this phase
          path.pop_back();
          continue;
        }
        const std::uint32_t v = adj[u][next[u]++];
        const std::uint32_t w = mate_r[v];
        if (w == kNone && dist[u] + 1 == found) {
          // Augment: the last left vertex takes v, each one before it its successor's old mate.
          std::uint32_t take = v;
          for (std::size_t k = path.size(); k-- > 0;) {
            const std::uint32_t x = path[k], old = mate_l[x];
            mate_l[x] = take;
            mate_r[take] = x;
            take = old;
          }
          ++size;
          for (const std::uint32_t x : path) dist[x] = kNone;  // used in this phase
          break;
        }
        if (w != kNone && dist[w] == dist[u] + 1) path.push_back(w);
      }
    }
  }
}

bool covers_far_points(const std::vector<PlanePoint>& s, const std::vector<PlanePoint>& o, double r) {
  std::vector<std::uint32_t> index(s.size(), std::numeric_limits<std::uint32_t>::max());
  std::vector<PlanePoint> far;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (diagonal(s[i]) > r) index[i] = static_cast<std::uint32_t>(far.size()), far.push_back(s[i]);
  std::vector<std::vector<std::uint32_t>> adj(far.size());
  pairs_within(far, o, r,
               [&](std::size_t i, std::size_t j, double) { adj[i].push_back(static_cast<std::uint32_t>(j)); });
  return hopcroft_karp(adj, o.size()) == far.size();
}

}  // namespace

bool explicit_bottleneck_feasible(const std::vector<PlanePoint>& a, const std::vector<PlanePoint>& b, double r) {
  return covers_far_points(a, b, r) && covers_far_points(b, a, r);
}

BottleneckCheck check_bottleneck(const std::vector<PlanePoint>& a, const std::vector<PlanePoint>& b, double value) {
  BottleneckCheck out;
  for (const auto* side : {&a, &b})
    for (const PlanePoint p : *side) {
      const double d = diagonal(p);
      out.is_candidate = out.is_candidate || d == value;
      if (d < value) out.below = std::max(out.below, d);
    }
  pairs_within(a, b, value, [&](std::size_t, std::size_t, double d) {
    out.is_candidate = out.is_candidate || d == value;
    if (d < value) out.below = std::max(out.below, d);
  });
  out.feasible = explicit_bottleneck_feasible(a, b, value);
  out.below_infeasible = out.below < 0 || !explicit_bottleneck_feasible(a, b, out.below);
  return out;
}

}  // namespace fnet::test
