// The Wasserstein matching between diagrams A and B as a min-cost flow with the diagonal as two
// hubs instead of n + m diagonal copies (the network: flow_state.hpp), solved by successive
// shortest paths (shortest_paths.hpp). Internal to the Wasserstein distance. The parts:
//   flow_state.hpp        the network, the flow and the potentials
//   shortest_paths.hpp    the runner: Dijkstra with potentials, early exit, augmentation
//   hub_arcs.hpp          the hubs' arcs as lazy streams in key order
//   pair_oracle.hpp       the 2-d trees with per-box potential maxima: bounds and cheapest arcs
//   candidate_arcs.hpp    the pair arcs the sparse searches scan
//   greedy_start.hpp      row reduction and column step
//   line_start.hpp        the programme's matching of a common death line, certified
//   dual_certificate.hpp  the LP dual over every pair: lower bound, violations, repairs
//   approximate_stop.hpp  a matching within an accept ratio of the dual bound
//   diagonal_flow_params.hpp  every tuning constant
// solve() works in stages ("seed, solve sparse, certify"):
//  0. Line start, where most points lie on one death line: the sorted-birth programme's optimal
//     matching of those points with certified potentials; the off-line points left are routed by
//     searches on the complete graph, which keep the certificate.
//  1. Otherwise a greedy start, then sparse searches on the candidates: each point's nearest
//     neighbours and the programme's pairs.
//  2. Certify: the LP dual is checked over every pair. A row with a violated arc gets its best
//     arcs added, its potential raised to feasible and is freed (with its partner) for the sparse
//     searches to route again; a few rounds.
//  3. Complete: rows still violating after those rounds are repaired the same way and finished by
//     searches on the complete graph.
// Either way an exact answer ends certified: every pair arc checked (stage 2) or searched (stage 3).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>

#include "common/distance/arc_power.hpp"
#include "common/distance/candidate_arcs.hpp"
#include "common/distance/diagonal_flow_params.hpp"
#include "common/distance/dual_certificate.hpp"
#include "common/distance/flow_state.hpp"
#include "common/distance/hub_arcs.hpp"
#include "common/distance/linf_kdtree.hpp"
#include "common/distance/pair_oracle.hpp"
#include "common/distance/shortest_paths.hpp"
#include "common/distance/sorted_birth_seed.hpp"

namespace fnet {

class DiagonalFlow {
 public:
  static constexpr std::int64_t kNone = FlowState::kNone, kDiagonal = FlowState::kDiagonal;

  // Arc costs power(length): a_i -> b_j power(||a_i - b_j||_inf), a_i -> HB and HA -> b_j the
  // power of the point's distance to the diagonal, |x - y| / 2.
  DiagonalFlow(std::span<const PlanePoint> a, std::span<const PlanePoint> b, ArcPower power,
               const DiagonalFlowParams& params = {});
  DiagonalFlow(const DiagonalFlow&) = delete;  // its parts refer to one another
  DiagonalFlow& operator=(const DiagonalFlow&) = delete;

  // Completes the flow to an optimal one (accept_ratio 1), or stops as soon as its cost is
  // certified within that ratio of the optimum: primal_cost() <= accept_ratio * dual_bound().
  void solve(double accept_ratio = 1);
  // The complete-graph searches alone from the current state (stage 3 only: the solver before
  // candidates, kept as the reference the benchmarks compare with); accept_ratio as for solve().
  void solve_complete(double accept_ratio = 1);
  // A lower bound on the optimal cost from the current potentials (LP duality), valid whenever
  // solve() or solve_complete() has returned; after an exact solve it equals primal_cost() up to
  // rounding: the optimality certificate.
  double dual_bound() const { return certificate_.dual_bound(flow_); }

  // The current flow's cost: matched pairs plus points sent to the diagonal.
  double primal_cost() const { return flow_.primal_cost(); }
  std::int64_t mate_of_a(std::uint32_t i) const { return flow_.mate_a[i]; }
  std::int64_t mate_of_b(std::uint32_t j) const { return flow_.mate_b[j]; }  // an index of A, kDiagonal or kNone
  const FlowState& state() const { return flow_; }                           // the flow, its mates among it

  // Potentials (dual variables): reduced cost of u -> v is cost + potential(u) - potential(v).
  std::span<const double> potentials() const { return flow_.pi; }  // a_0..a_{n-1}, b_0..b_{m-1}, HA, HB
  double diagonal_a(std::uint32_t i) const { return flow_.da[i]; }
  double diagonal_b(std::uint32_t j) const { return flow_.db[j]; }
  std::size_t augmentations() const { return paths_.augmentations(); }
  std::size_t settled() const { return paths_.settled(); }
  std::size_t boxes_opened() const { return paths_.boxes_opened(); }
  std::size_t certify_rounds() const { return certificate_.rounds(); }   // LP-dual checks over every pair
  std::size_t repaired_rows() const { return certificate_.repaired(); }  // rows freed by a violated arc
  std::size_t candidate_arcs() const { return candidates_.size(); }      // pair arcs the sparse searches scan
  bool finished_on_complete_graph() const { return completed_; }
  bool started_on_line() const { return on_line_; }  // the line start was taken (stage 0)

 private:
  void start_greedy();
  // The sorted-birth programme's alignment; on a common line (on_line) its band doubles until
  // the programme's path keeps off the band's edges, the band holds every column, or the next
  // band would pass params_.max_band_cells.
  LineAlignment align_sorted_births(bool on_line) const;
  // Stage 2 from a routed flow: rounds of "check every pair, add the violated arcs, free their
  // rows, route them again" until certified (or, with accept_ratio > 1, within the ratio); past
  // params_.max_rounds rounds, or with params_.few_rows rows left, stage 3 finishes.
  void repair_rounds(double accept_ratio);
  // Routes the diagonal's remaining units, then every free row; with accept_ratio > 1 it may stop
  // (true) once primal_cost() <= accept_ratio * dual_bound(), the free points on the diagonal.
  bool augment_all(double accept_ratio = 1);
  // Approximate solves: the free rows lowered, whether finish(accept_ratio * dual bound) found a
  // matching that costs no more (approximate_stop.hpp).
  bool finished_within(double accept_ratio, const std::function<bool(double)>& finish);
  // The candidates of stage 1: the programme's pairs and the nearest neighbours of every point, or
  // (line start) of the off-line points only.
  void build_candidates(const LineAlignment& alignment, bool off_line_only);
  void add_nearest_candidates(std::optional<double> skip_line);

  DiagonalFlowParams params_;
  FlowState flow_;
  HubArcs hubs_;
  PairOracle oracle_;
  CandidateArcs candidates_;
  DualCertificate certificate_;
  ShortestPaths paths_;
  bool started_ = false;    // a start (greedy or line) has set the flow
  bool on_line_ = false;    // the line start was taken
  bool completed_ = false;  // the complete-graph searches ran
};

}  // namespace fnet
