// The Wasserstein matching between diagrams A and B as a min-cost flow, with the diagonal as two
// hubs instead of n + m diagonal copies:
//   a_i -> b_j   cost c_ij (candidate arcs only), a_i -> HB cost da_i (a_i to the diagonal),
//   HA  -> b_j   cost db_j (b_j from the diagonal),  HA -> HB cost 0, unbounded.
// Supplies: a_i 1, HA m; demands: b_j 1, HB n. Solved by successive shortest paths (Dijkstra with
// potentials, early exit); the hubs' many arcs are scanned lazily from ordered sets, so a search
// costs what it visits, not O(n + m). Internal to the Wasserstein distance.
#pragma once

#include <cstdint>
#include <set>
#include <span>
#include <utility>
#include <vector>

namespace fnet {

class DiagonalFlow {
 public:
  static constexpr std::int64_t kNone = -1, kDiagonal = -2;

  struct Arc {
    std::uint32_t row, col;
    double cost;
  };

  // Costs to the diagonal, already raised to the power q. Arcs: candidate pairs (a_i, b_j).
  DiagonalFlow(std::vector<double> diagonal_a, std::vector<double> diagonal_b, std::vector<Arc> arcs);

  // Completes the flow to an optimal one on the current arcs; keeps what it has (warm start).
  void solve();

  // Adds arcs (pairs already present are skipped); every row that gets one is released: its unit
  // goes back to its source and its potential is raised to keep all reduced costs >= 0.
  void add_arcs(std::vector<Arc> arcs);
  bool has_arc(std::uint32_t row, std::uint32_t col) const;

  // The current flow's cost: matched pairs plus points sent to the diagonal.
  double primal_cost() const;
  std::int64_t mate_of_a(std::uint32_t i) const { return mate_a_[i]; }

  // Potentials (dual variables): reduced cost of u -> v is cost + potential(u) - potential(v).
  std::span<const double> potentials() const { return pi_; }  // a_0..a_{n-1}, b_0..b_{m-1}, HA, HB
  double diagonal_a(std::uint32_t i) const { return da_[i]; }
  double diagonal_b(std::uint32_t j) const { return db_[j]; }
  std::size_t augmentations() const { return augmentations_; }

  // The dual objective of the current potentials over every arc except the pairs (a_i, b_j),
  // whose negative reduced costs the caller subtracts: sum of demand * potential, minus the
  // capacity-weighted negative reduced costs of the hub arcs. A lower bound on the optimum once
  // the pairs are accounted for, whatever the potentials.
  double dual_without_pairs() const;

 private:
  void rebuild_rows(std::vector<Arc> arcs);
  bool dijkstra(std::uint32_t source);
  void relax(std::uint32_t v, double d, std::uint32_t from, double cost);
  void scan(std::uint32_t u, double d);
  void push_generator(int which);
  void refresh(std::uint32_t node);
  bool is_sink(std::uint32_t v) const;

  std::uint32_t n_, m_, ha_, hb_;
  std::vector<double> da_, db_;
  std::vector<std::uint32_t> row_start_, row_col_;
  std::vector<double> row_cost_;

  std::vector<std::int64_t> mate_a_, mate_b_;  // partner index, kDiagonal or kNone
  std::vector<double> mate_cost_a_;
  std::int64_t flow_hub_ = 0, b_from_diagonal_ = 0, a_to_diagonal_ = 0;
  std::vector<double> pi_;

  // Lazy hub arcs: HA -> b_j for b_j not fed by HA, keyed db_j - pi(b_j); HB -> a_i for a_i sent
  // to the diagonal, keyed -da_i - pi(a_i).
  std::set<std::pair<double, std::uint32_t>> hub_a_, hub_b_;
  std::vector<double> key_;   // the key a node is filed under, NaN if not filed
  using Cursor = std::set<std::pair<double, std::uint32_t>>::const_iterator;
  Cursor cursor_[2];
  double hub_dist_[2] = {0, 0};

  // Dijkstra workspace.
  std::uint32_t run_ = 0;
  std::vector<double> dist_, pred_cost_;
  std::vector<std::uint32_t> pred_, seen_, final_;
  std::vector<std::uint32_t> finalized_, path_;
  std::vector<std::pair<double, std::int64_t>> heap_;
  std::size_t augmentations_ = 0;
};

}  // namespace fnet
