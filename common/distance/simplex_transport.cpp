#include "common/distance/simplex_transport.hpp"

#include <algorithm>
#include <optional>

#include "common/distance/candidate_arcs.hpp"
#include "common/distance/line_seed.hpp"
#include "common/distance/network_simplex.hpp"
#include "common/distance/work_deadline.hpp"

namespace fnet {

namespace {

bool beats_diagonal(const FlowState& flow, std::uint32_t i, std::uint32_t j) {
  return flow.cost(i, j) < flow.da[i] + flow.db[j];
}

bool holds(const CandidateArcs& graph, std::uint32_t i, std::uint32_t j) {
  const auto row = graph.row(i);
  return std::binary_search(row.begin(), row.end(), j);
}

// The simplex's flow and potentials into the FlowState (mates, counters, pi).
void copy_out(const NetworkSimplex& simplex, FlowState& flow) {
  const std::vector<std::int64_t> mate = simplex.mates_of_a();
  std::fill(flow.mate_b.begin(), flow.mate_b.end(), FlowState::kDiagonal);
  flow.a_to_diagonal = 0;
  flow.flow_hub = 0;
  for (std::uint32_t i = 0; i < flow.n; ++i) {
    if (mate[i] >= 0) {
      const auto j = static_cast<std::uint32_t>(mate[i]);
      flow.mate_a[i] = j;
      flow.mate_b[j] = i;
      flow.mate_cost_a[i] = flow.cost(i, j);
      ++flow.flow_hub;
    } else {
      flow.mate_a[i] = FlowState::kDiagonal;
      ++flow.a_to_diagonal;
    }
  }
  flow.b_from_diagonal = static_cast<std::int64_t>(flow.m) - flow.flow_hub;
  const auto pi = simplex.potentials();
  std::copy(pi.begin(), pi.end(), flow.pi.begin());
}

}  // namespace

void solve_by_simplex(FlowState& flow, PairOracle& oracle, DualCertificate& certificate, double accept_ratio,
                      const SimplexTransportParams& params, SimplexTransportStats& stats) {
  stats = {};
  LineSeed seed;
  if (params.line_min_points > 0)
    seed = line_seed(flow, params.band, params.max_band_cells, params.line_min_points, params.line_ranks);
  std::vector<NetworkSimplex::PairStart> start;
  for (const auto& [i, j] : seed.pairs) start.push_back({i, j, flow.cost(i, j)});
  NetworkSimplex simplex(flow.da, flow.db, start);
  CandidateArcs graph(flow.n);
  graph.add(seed.pairs);
  PairArcs fresh;
  const auto add = [&](PairArcs& arcs) {
    std::sort(arcs.begin(), arcs.end());
    arcs.erase(std::unique(arcs.begin(), arcs.end()), arcs.end());
    for (const auto& [i, j] : arcs) simplex.add_pair_arc(i, j, flow.cost(i, j));
    graph.add(arcs);
  };
  // Every point's nearest neighbours (also the line's: leaving them to the seed's candidates took
  // more pricing rounds, tests/bench/notes.md).
  std::vector<std::uint32_t> near;
  const auto keep = [&](std::uint32_t i, std::uint32_t j) {
    if (beats_diagonal(flow, i, j) && !holds(graph, i, j)) fresh.push_back({i, j});
  };
  for (std::uint32_t i = 0; i < flow.n; ++i) {
    oracle.tree_b().nearest(flow.a[i], params.nearest, near, i);
    for (const std::uint32_t j : near) keep(i, j);
  }
  for (std::uint32_t j = 0; j < flow.m; ++j) {
    oracle.tree_a().nearest(flow.b[j], params.nearest, near, j);
    for (const std::uint32_t i : near) keep(i, j);
  }
  for (const auto& [i, j] : seed.candidates)
    if (beats_diagonal(flow, i, j) && !holds(graph, i, j)) fresh.push_back({i, j});
  add(fresh);
  stats.initial_arcs = graph.size();
  for (;;) {
    simplex.solve();
    copy_out(simplex, flow);
    check_work_deadline_now();
    oracle.recompute_all();
    certificate.check_pairs(flow, oracle, params.top_arcs);
    ++stats.rounds;
    fresh.clear();
    for (const auto& [i, j] : certificate.violated_arcs())
      if (!holds(graph, i, j) && beats_diagonal(flow, i, j)) fresh.push_back({i, j});
    certificate.clear_violations();
    // No violation beyond rounding but pairs already in the graph (whose reduced costs the simplex
    // holds >= -its tolerance): certified; what rounding left is charged to the dual bound.
    if (fresh.empty()) {
      stats.certified = true;
      break;
    }
    if (accept_ratio > 1 && flow.primal_cost() <= accept_ratio * certificate.dual_bound(flow)) break;
    if (stats.rounds >= params.max_rounds) break;
    add(fresh);
  }
  stats.pivots = simplex.pivots();
  stats.degenerate_pivots = simplex.degenerate_pivots();
  stats.pair_arcs = graph.size();
}

}  // namespace fnet
