#include "common/persistence.hpp"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <limits>
#include <vector>

#include "common/union_find.hpp"

namespace fnet {
namespace {

using Index = std::uint32_t;
constexpr Index kNone = std::numeric_limits<Index>::max();

// Adjacency in CSR form; each neighbour carries the filtration position of the connecting edge.
struct Adjacency {
  std::vector<Index> start;  // vertex_count + 1 offsets
  std::vector<Index> neighbour;
  std::vector<Index> edge;

  explicit Adjacency(const ForceNetwork& net) : start(net.vertex_count + 1, 0) {
    for (const Edge& e : net.edges) {
      ++start[e.u + 1];
      ++start[e.v + 1];
    }
    for (std::size_t v = 0; v < net.vertex_count; ++v) start[v + 1] += start[v];
    neighbour.resize(start.back());
    edge.resize(start.back());
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (Index k = 0; k < net.edges.size(); ++k) {
      const Edge& e = net.edges[k];
      neighbour[fill[e.u]] = e.v, edge[fill[e.u]++] = k;
      neighbour[fill[e.v]] = e.u, edge[fill[e.v]++] = k;
    }
    // Sorted neighbour lists allow binary search when closing triangles.
    std::vector<std::pair<Index, Index>> buf;
    for (std::size_t v = 0; v < net.vertex_count; ++v) {
      buf.clear();
      for (Index a = start[v]; a < start[v + 1]; ++a) buf.emplace_back(neighbour[a], edge[a]);
      std::sort(buf.begin(), buf.end());
      for (Index a = start[v], b = 0; a < start[v + 1]; ++a, ++b) neighbour[a] = buf[b].first, edge[a] = buf[b].second;
    }
  }

  Index degree(Index v) const { return start[v + 1] - start[v]; }

  // Filtration position of edge (v, w), or kNone.
  Index find_edge(Index v, Index w) const {
    const auto first = neighbour.begin() + start[v], last = neighbour.begin() + start[v + 1];
    const auto it = std::lower_bound(first, last, w);
    return it != last && *it == w ? edge[static_cast<std::size_t>(it - neighbour.begin())] : kNone;
  }
};

// PD0 by union-find in filtration order (elder rule). Marks the edges that close a cycle: only
// those can be born in PD1.
Diagram components(const ForceNetwork& net, std::vector<bool>& closes_cycle) {
  Diagram pd0;
  const std::size_t n = net.vertex_count;
  constexpr double kAbsent = -std::numeric_limits<double>::infinity();
  std::vector<double> birth(n, kAbsent);  // of the component rooted here; absent until touched
  UnionFind sets(n);
  closes_cycle.assign(net.edges.size(), false);
  for (Index k = 0; k < net.edges.size(); ++k) {
    const Edge& e = net.edges[k];
    if (birth[e.u] == kAbsent) birth[e.u] = e.value;  // a vertex enters with its strongest edge
    if (birth[e.v] == kAbsent) birth[e.v] = e.value;
    Index a = sets.find(e.u), b = sets.find(e.v);
    if (a == b) {
      closes_cycle[k] = true;
      continue;
    }
    if (birth[a] < birth[b]) std::swap(a, b);  // a is the elder
    if (birth[b] > e.value) pd0.push_back({birth[b], e.value});
    sets.attach(b, a);
  }
  for (Index v = 0; v < n; ++v) {
    if (sets.find(v) != v) continue;
    pd0.push_back({birth[v] == kAbsent ? 0.0 : birth[v], kNeverDies});  // rattlers: (0, -1)
  }
  return pd0;
}

// Triangles as sorted triples of edge positions, in filtration order: a triangle enters with its
// weakest (latest) edge, so ordering by (p3, p2) refines the order of values.
struct Triangle {
  Index p1, p2, p3;
};

std::vector<Triangle> triangles_in_filtration_order(const ForceNetwork& net, const Adjacency& adj) {
  std::vector<Triangle> out;
  std::vector<Triangle> here;
  for (Index k = 0; k < net.edges.size(); ++k) {
    Index u = net.edges[k].u, v = net.edges[k].v;
    if (adj.degree(u) > adj.degree(v)) std::swap(u, v);
    here.clear();
    for (Index a = adj.start[u]; a < adj.start[u + 1]; ++a) {
      const Index uw = adj.edge[a];
      if (uw >= k) continue;
      const Index vw = adj.find_edge(v, adj.neighbour[a]);
      if (vw == kNone || vw >= k) continue;
      here.push_back({std::min(uw, vw), std::max(uw, vw), k});
    }
    std::sort(here.begin(), here.end(), [](const Triangle& x, const Triangle& y) { return x.p2 < y.p2; });
    out.insert(out.end(), here.begin(), here.end());
  }
  return out;
}

// Z/2 reduction of the triangle boundary columns (homology, standard algorithm). Columns that
// own a pivot are kept in one pool; a column is a sorted list of edge positions.
Diagram loops(const ForceNetwork& net, const std::vector<Triangle>& triangles, const std::vector<bool>& closes_cycle) {
  Diagram pd1;
  const auto& edges = net.edges;
  std::vector<Index> owner_start(edges.size(), kNone);  // pivot edge -> its column in the pool
  std::vector<Index> owner_size(edges.size(), 0);
  std::vector<Index> pool;
  pool.reserve(3 * triangles.size());
  std::vector<Index> column, sum;
  for (const Triangle& t : triangles) {
    if (owner_start[t.p3] == kNone) {  // apparent pair (p3, t): zero persistence, nothing to report
      owner_start[t.p3] = static_cast<Index>(pool.size());
      owner_size[t.p3] = 3;
      pool.insert(pool.end(), {t.p1, t.p2, t.p3});
      continue;
    }
    column.assign({t.p1, t.p2, t.p3});
    while (!column.empty() && owner_start[column.back()] != kNone) {
      const Index pivot = column.back();
      const auto other = pool.begin() + owner_start[pivot];
      sum.clear();
      std::set_symmetric_difference(column.begin(), column.end(), other, other + owner_size[pivot],
                                    std::back_inserter(sum));
      column.swap(sum);
    }
    if (column.empty()) continue;  // the triangle closes a 2-cycle (possible in non-planar graphs)
    const Index pivot = column.back();
    assert(closes_cycle[pivot]);
    owner_start[pivot] = static_cast<Index>(pool.size());
    owner_size[pivot] = static_cast<Index>(column.size());
    pool.insert(pool.end(), column.begin(), column.end());
    const double birth = edges[pivot].value, death = edges[t.p3].value;
    if (birth > death) pd1.push_back({birth, death});
  }
  for (Index k = 0; k < edges.size(); ++k)
    if (closes_cycle[k] && owner_start[k] == kNone) pd1.push_back({edges[k].value, kNeverDies});
  return pd1;
}

}  // namespace

FrameDiagrams compute_persistence(const ForceNetwork& network) {
  FrameDiagrams out;
  out.vertices = network.vertex_count;
  out.edges = network.edges.size();
  std::vector<bool> closes_cycle;
  out.pd0 = components(network, closes_cycle);
  const Adjacency adjacency(network);
  const std::vector<Triangle> triangles = triangles_in_filtration_order(network, adjacency);
  out.triangles = triangles.size();
  out.pd1 = loops(network, triangles, closes_cycle);
  sort_canonical(out.pd0);
  sort_canonical(out.pd1);
  return out;
}

}  // namespace fnet
