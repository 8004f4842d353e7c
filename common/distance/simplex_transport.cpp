#include "common/distance/simplex_transport.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "common/distance/candidate_arcs.hpp"
#include "common/distance/line_seed.hpp"
#include "common/distance/network_simplex.hpp"
#include "common/distance/sorted_birth_seed.hpp"
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
                      const SimplexTransportParams& given, SimplexTransportStats& stats) {
  SimplexTransportParams params = given;
#ifdef FNET_SIMPLEX_KNOBS
  if (std::getenv("NS_K")) params.nearest = std::atoi(std::getenv("NS_K"));
  if (std::getenv("NS_TOP")) params.top_arcs = std::atoi(std::getenv("NS_TOP"));
  if (std::getenv("NS_LINE")) params.line_min_points = std::atoi(std::getenv("NS_LINE"));
  if (std::getenv("NS_RANKS")) params.line_ranks = std::atoi(std::getenv("NS_RANKS"));
#endif
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
  // Nearest neighbours as they are, and after the median scale between the two diagrams (forces
  // are in units of their frame's mean, which moves between frames: the whole diagram stretches).
  const double scale = quantile_scale(flow.a, flow.b);
  for (const double s : {1.0, scale}) {
    if (s != 1.0 && (s == scale) && scale == 1.0) continue;
    for (const auto& [i, j] :
         nearest_arcs(flow.a, flow.b, oracle.tree_a(), oracle.tree_b(), params.nearest, s, std::nullopt))
      if (beats_diagonal(flow, i, j) && !holds(graph, i, j)) fresh.push_back({i, j});
    if (scale == 1.0) break;
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
#ifdef FNET_SIMPLEX_KNOBS
    if (std::getenv("NS_TRACE"))
      std::fprintf(stderr,
                   "round %zu rebuilds %zu refreshes %zu scanned %zu deg %zu pivots %zu fresh %zu arcs %zu primal "
                   "%.17g dual %.17g\n",
                   stats.rounds, simplex.rebuilds_, simplex.refreshes_, simplex.scanned_total_,
                   simplex.degenerate_pivots(), simplex.pivots(), fresh.size(), graph.size(), flow.primal_cost(),
                   certificate.dual_bound(flow));
#endif
    add(fresh);
  }
#ifdef FNET_SIMPLEX_KNOBS
  if (std::getenv("NS_TRACE")) {
    CandidateArcs initial(flow.n);
    PairArcs first;
    for (const auto& [i, j] : seed.pairs) first.push_back({i, j});
    for (const auto& [i, j] : seed.candidates) first.push_back({i, j});
    for (const auto& [i, j] :
         nearest_arcs(flow.a, flow.b, oracle.tree_a(), oracle.tree_b(), params.nearest, 1.0, std::nullopt))
      first.push_back({i, j});
    initial.add(first);
    std::size_t missing[4] = {0, 0, 0, 0}, total[4] = {0, 0, 0, 0};
    double line = 0;
    for (std::uint32_t i = 0; i < flow.n; ++i)
      if (flow.a[i].y == 0) line = 0;
    for (std::uint32_t i = 0; i < flow.n; ++i) {
      if (flow.mate_a[i] < 0) continue;
      const auto j = static_cast<std::uint32_t>(flow.mate_a[i]);
      const int kind = (flow.a[i].y == line ? 0 : 2) + (flow.b[j].y == line ? 0 : 1);
      ++total[kind];
      if (!holds(initial, i, j)) ++missing[kind];
    }
    std::fprintf(
        stderr, "missing pairs line-line %zu/%zu line-off %zu/%zu off-line %zu/%zu off-off %zu/%zu; seed pairs %zu\n",
        missing[0], total[0], missing[1], total[1], missing[2], total[2], missing[3], total[3], seed.pairs.size());
  }
#endif
  stats.pivots = simplex.pivots();
  stats.degenerate_pivots = simplex.degenerate_pivots();
  stats.pair_arcs = graph.size();
}

}  // namespace fnet
