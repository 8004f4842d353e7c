// fnet's exact W1 against LEMON's network simplex (liblemon-dev) on the same diagram pairs, from
// one run: the question the distance issue asked, whether a general min-cost-flow solver beats
// fnet's own. LEMON gets W1 in its most favourable exact form, a sparse graph: L-infinity is L1
// after a 45-degree turn (u = x + y, v = x - y: ||p - q||_inf = (|du| + |dv|) / 2), and L1
// distances are path lengths in a Steiner graph of O(n log n) arcs (split the points at the
// median u, give each point a node on the split line at its own v, chain those nodes by v, and
// recurse on both halves), plus one diagonal node (each point |v| / 2 away). Its optimum is W1
// exactly; the value column shows both agree.
//   bench_lemon [--repeat R] A.json B.json [A2.json B2.json ...]
// Files: fnet-analyze diagram output; pd0 and pd1 of each pair, floor convention (never-dying
// classes die at 0), fnet through wasserstein_distance, LEMON's time including the graph build.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <lemon/network_simplex.h>
#include <lemon/smart_graph.h>
#include <string>
#include <vector>

#include "common/distance/wasserstein.hpp"
#include "tests/bench/distance/bench_inputs.hpp"

using namespace fnet;

namespace {

struct SteinerArc {
  int tail, head;
  double cost;
};

// W1 between the finite points of a and b (floor: death -1 is 0) by LEMON's network simplex.
double lemon_w1(const Diagram& a, const Diagram& b) {
  std::vector<double> u, v;
  int n = 0, m = 0;
  for (const Diagram* d : {&a, &b}) {
    for (const PersistencePoint& p : *d) {
      const double death = p.death == kNeverDies ? 0 : p.death;
      if (p.birth == death) continue;
      u.push_back(p.birth + death), v.push_back(p.birth - death);
      ++(d == &a ? n : m);
    }
  }
  // Nodes: the points of a, then of b, the diagonal, then the Steiner nodes.
  const int diagonal = n + m;
  int nodes = n + m + 1;
  std::vector<SteinerArc> arcs;
  for (int k = 0; k < n + m; ++k) {
    if (k < n) {
      arcs.push_back({k, diagonal, std::fabs(v[k]) / 2});
    } else {
      arcs.push_back({diagonal, k, std::fabs(v[k]) / 2});
    }
  }
  std::vector<int> order(n + m);
  for (int k = 0; k < n + m; ++k) order[k] = k;
  std::vector<std::pair<double, int>> by_v;
  const auto split = [&](auto&& self, int lo, int hi) -> void {
    if (hi - lo <= 1) return;
    const int mid = (lo + hi) / 2;
    std::nth_element(order.begin() + lo, order.begin() + mid, order.begin() + hi,
                     [&](int p, int q) { return u[p] < u[q]; });
    const double line = u[order[mid]];
    by_v.clear();
    for (int k = lo; k < hi; ++k) by_v.push_back({v[order[k]], order[k]});
    std::sort(by_v.begin(), by_v.end());
    int last = -1;
    for (std::size_t k = 0; k < by_v.size(); ++k) {
      if (k == 0 || by_v[k].first != by_v[k - 1].first) {
        const int node = nodes++;
        if (last >= 0) {
          const double gap = (by_v[k].first - by_v[k - 1].first) / 2;
          arcs.push_back({last, node, gap}), arcs.push_back({node, last, gap});
        }
        last = node;
      }
      const int p = by_v[k].second;  // points of a only send, of b only receive
      const double reach = std::fabs(u[p] - line) / 2;
      if (p < n) {
        arcs.push_back({p, last, reach});
      } else {
        arcs.push_back({last, p, reach});
      }
    }
    self(self, lo, mid);
    self(self, mid, hi);
  };
  split(split, 0, n + m);

  lemon::SmartDigraph g;
  g.reserveNode(nodes);
  g.reserveArc(static_cast<int>(arcs.size()));
  for (int k = 0; k < nodes; ++k) g.addNode();
  lemon::SmartDigraph::ArcMap<double> cost(g);
  for (const SteinerArc& arc : arcs) cost[g.addArc(g.nodeFromId(arc.tail), g.nodeFromId(arc.head))] = arc.cost;
  lemon::SmartDigraph::NodeMap<long> supply(g, 0);
  for (int k = 0; k < n + m; ++k) supply[g.nodeFromId(k)] = k < n ? 1 : -1;
  supply[g.nodeFromId(diagonal)] = m - n;
  lemon::NetworkSimplex<lemon::SmartDigraph, long, double> simplex(g);
  simplex.costMap(cost).supplyMap(supply);
  if (simplex.run() != lemon::NetworkSimplex<lemon::SmartDigraph, long, double>::OPTIMAL) {
    std::fprintf(stderr, "bench_lemon: the network simplex found no optimum\n");
    std::exit(1);
  }
  return simplex.totalCost();
}

template <class F>
double median_ms(int repeat, F f, double& value) {
  std::vector<double> times;
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    value = f();
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() * 1e3);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const auto [repeat, files] = bench::parse_pair_args(argc, argv, "bench_lemon", 5);
  std::printf("%-44s %3s %6s %10s %10s %8s %18s %18s\n", "pair", "dim", "pts", "fnet ms", "LEMON ms", "LEMON/fnet",
              "fnet W1", "LEMON W1");
  for (std::size_t f = 0; f < files.size(); f += 2) {
    for (int dim = 0; dim < 2; ++dim) {
      const Diagram a = bench::load_diagram(files[f], dim), b = bench::load_diagram(files[f + 1], dim);
      double ours = 0, theirs = 0;
      const double t_ours = median_ms(
          repeat, [&] { return wasserstein_distance(a, b, {.q = 1}).value; }, ours);
      const double t_theirs = median_ms(
          repeat, [&] { return lemon_w1(a, b); }, theirs);
      const std::string name = bench::pair_name(files[f], files[f + 1]);
      std::printf("%-44s %3d %6zu %10.2f %10.2f %9.1fx %18.12g %18.12g\n", name.c_str(), dim,
                  std::max(a.size(), b.size()), t_ours, t_theirs, t_theirs / t_ours, ours, theirs);
    }
  }
  return 0;
}
