// The Wasserstein matching between diagrams A and B as a min-cost flow, with the diagonal as two
// hubs instead of n + m diagonal copies:
//   a_i -> b_j   cost c_ij, a_i -> HB cost da_i (a_i to the diagonal),
//   HA  -> b_j   cost db_j (b_j from the diagonal),  HA -> HB cost 0, unbounded.
// Supplies: a_i 1, HA m; demands: b_j 1, HB n. Solved by successive shortest paths (Dijkstra with
// potentials, early exit, a radix heap: monotone_heap.hpp); the hubs' many arcs are scanned lazily,
// in key order, from indexed heaps (keyed_index.hpp), so a search costs what it visits, not
// O(n + m). Internal to the Wasserstein distance.
//
// Pair arcs: every pair (a_i, b_j) with c_ij < da_i + db_j (the others never beat sending both to
// the diagonal), never stored. solve() works in three stages ("seed, solve sparse, certify"):
//  1. Candidates: each point's nearest neighbours on the other side and the pairs of the
//     sorted-birth dynamic programme (sorted_birth_seed.hpp); the searches scan only those.
//  2. Certify: the LP dual is checked over every pair with the 2-d tree over B (per box the max of
//     pi(b)). A row with a violated arc gets its best arc added, its potential raised to feasible
//     and is freed (with its partner) for the searches to route again; a few rounds.
//  3. Complete: rows still violating after those rounds are repaired the same way and finished by
//     searches on the complete graph: when Dijkstra settles a_i it enters the 2-d tree over B
//     (its nearest leaf, then that leaf's ancestors' other children) as heap entries keyed by a
//     lower bound on the reduced cost of any arc into a box: power(box distance) + pi(a_i) -
//     max pi(b) over the box (when costs are the lengths themselves also the bounds from
//     |x_i - x_j| and |y_i - y_j| against max pi(b) -+ x_b, -+ y_b, which follow potentials
//     sloping across the box). Boxes are opened best first, boxes whose points are all settled
//     are skipped, so this search is exact on the complete graph.
// Either way the answer ends certified: every pair arc checked (stage 2) or searched (stage 3).
// Where most points lie on one death line (floor PD1s, ~90 %), the flow starts instead from the
// programme's optimal matching of those points, whose potentials come from label-correcting sweeps
// on the candidates, certified over every pair like stage 2 (violated arcs added, the potentials
// lowered again, the flow untouched); the off-line points left are routed by stage 3's searches.
// Otherwise the flow starts from a row reduction (each a_i takes its cheapest way out when free) and a
// column step for the b_j left free (fed from the diagonal when that is their cheapest way in);
// the diagonal's remaining units are routed before the remaining rows.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "common/distance/arc_power.hpp"
#include "common/distance/keyed_index.hpp"
#include "common/distance/linf_kdtree.hpp"
#include "common/distance/monotone_heap.hpp"
#include "common/distance/sorted_birth_seed.hpp"

namespace fnet {

class DiagonalFlow {
 public:
  static constexpr std::int64_t kNone = -1, kDiagonal = -2;

  // Arc costs power(length): a_i -> b_j power(||a_i - b_j||_inf), a_i -> HB and HA -> b_j the
  // power of the point's distance to the diagonal, |x - y| / 2.
  DiagonalFlow(std::span<const PlanePoint> a, std::span<const PlanePoint> b, ArcPower power);

  // Completes the flow to an optimal one (accept_ratio 1), or stops as soon as its cost is
  // certified within that ratio of the optimum: primal_cost() <= accept_ratio * dual_bound().
  void solve(double accept_ratio = 1);
  // The complete-graph searches alone from the current state (stage 3 only: the solver before
  // candidates, kept as the reference the benchmarks compare with); accept_ratio as for solve().
  void solve_complete(double accept_ratio = 1);
  // A lower bound on the optimal cost from the current potentials (LP duality), valid whenever
  // solve() or solve_complete() has returned; after an exact solve it equals primal_cost() up to
  // rounding: the optimality certificate.
  double dual_bound() const;

  // The current flow's cost: matched pairs plus points sent to the diagonal.
  double primal_cost() const;
  std::int64_t mate_of_a(std::uint32_t i) const { return mate_a_[i]; }
  std::int64_t mate_of_b(std::uint32_t j) const { return mate_b_[j]; }  // an index of A, kDiagonal or kNone

  // Potentials (dual variables): reduced cost of u -> v is cost + potential(u) - potential(v).
  std::span<const double> potentials() const { return pi_; }  // a_0..a_{n-1}, b_0..b_{m-1}, HA, HB
  double diagonal_a(std::uint32_t i) const { return da_[i]; }
  double diagonal_b(std::uint32_t j) const { return db_[j]; }
  std::size_t augmentations() const { return augmentations_; }
  std::size_t settled() const { return settled_; }
  std::size_t boxes_opened() const { return boxes_opened_; }
  std::size_t certify_rounds() const { return rounds_; }       // LP-dual checks over every pair
  std::size_t repaired_rows() const { return repaired_; }      // rows freed by a violated arc
  std::size_t candidate_arcs() const { return cand_.size(); }  // pair arcs the sparse searches scan
  bool finished_on_complete_graph() const { return completed_; }
  bool started_on_line() const { return on_line_; }  // the line start was taken (stage 0)

 private:
  // Nodes: a_0..a_{n-1}, then b_0..b_{m-1}, then the hubs HA and HB.
  bool is_a(std::uint32_t v) const { return v < n_; }
  bool is_b(std::uint32_t v) const { return v >= n_ && v < n_ + m_; }
  std::uint32_t node_of_b(std::uint32_t j) const { return n_ + j; }
  std::uint32_t b_of_node(std::uint32_t v) const { return v - n_; }

  // Heap entries, ordered by (key, id): a node (its id), a hub's lazy arc stream (negative), or a
  // tree box entered for a row (kBoxBase + its index in boxes_). At equal keys streams pop first,
  // then nodes, then boxes: a sink found at the current distance ends the search before any box
  // that cannot beat it is opened.
  static constexpr std::int64_t kBoxBase = std::int64_t{1} << 40;
  static constexpr int kStreamHa = 0, kStreamHb = 1;  // HA -> b_j (hub_a_), HB -> a_i (hub_b_)
  static std::int64_t stream_entry(int stream) { return -1 - stream; }
  static bool is_stream_entry(std::int64_t id) { return id < 0; }
  static int stream_of_entry(std::int64_t id) { return static_cast<int>(-1 - id); }
  static bool is_box_entry(std::int64_t id) { return id >= kBoxBase; }
  void push(double key, std::int64_t id);
  void push_box(std::uint32_t row, std::int32_t node, double key);

  // A shortest path from source to a sink, then augment; false when no sink is reachable.
  bool dijkstra(std::uint32_t source);
  void augment(std::uint32_t source, std::uint32_t target);
  void relax(std::uint32_t v, double d, std::uint32_t from, double cost);
  void scan(std::uint32_t u, double d);
  // The hubs' arcs are offered lazily, in key order, as one heap entry per hub at a time.
  KeyedIndex& stream_arcs(int stream);  // (key, index of a_i or b_j)
  std::uint32_t stream_node(int stream, std::uint32_t index) const;
  std::uint32_t stream_hub(int stream) const;
  bool skip_settled(int stream);            // walks past settled heads; false at the end
  void push_stream(int stream);             // files the stream's next arc in the heap
  void start_stream(int stream, double d);  // the hub is settled at distance d
  void pop_stream(int stream);              // relaxes the stream's next arc
  void refresh(std::uint32_t node);
  bool is_sink(std::uint32_t v) const;
  double cost(std::uint32_t i, std::uint32_t j) const;
  // A lower bound on c_ij - pi(b_j) over the pair arcs from a_i into the box (+inf: none beats
  // the diagonal); the searches' box keys and the certificate's pruning both use it.
  double box_price_bound(std::uint32_t i, std::int32_t node) const;
  double box_key(std::uint32_t i, std::int32_t node) const;
  void open_box(std::uint32_t i, std::int32_t node);
  void update_box_maxima(std::uint32_t j);
  // The leaf of the tree over B nearest a_i (by box distance, from the root down), found once.
  std::int32_t home_leaf(std::uint32_t i);
  std::vector<std::int32_t> home_leaf_;

  std::uint32_t n_, m_, ha_, hb_;
  ArcPower power_;
  std::vector<double> da_, db_;  // costs to the diagonal

  std::vector<std::int64_t> mate_a_, mate_b_;  // partner index, kDiagonal or kNone
  std::vector<double> mate_cost_a_;
  std::int64_t flow_hub_ = 0, b_from_diagonal_ = 0, a_to_diagonal_ = 0;
  std::vector<double> pi_;

  // Lazy hub arcs: HA -> b_j for b_j not fed by HA, keyed db_j - pi(b_j); HB -> a_i for a_i sent
  // to the diagonal, keyed -da_i - pi(a_i).
  KeyedIndex hub_a_, hub_b_;     // each walked from its head when its hub is settled
  double hub_dist_[2] = {0, 0};  // per stream: the distance of its hub

  // The tree over B, per node the max of pi(b) (an upper bound: potentials only fall
  // between refreshes), each node's parent and each point's leaf.
  std::vector<PlanePoint> pa_;
  std::unique_ptr<LinfKdTree> tree_b_;
  struct BoxMax {  // over the box's points b: max pi(b), max pi(b) -+ x_b, max pi(b) -+ y_b
    double pi = -kHuge, minus_x = -kHuge, plus_x = -kHuge, minus_y = -kHuge, plus_y = -kHuge;
  };
  static constexpr double kHuge = 1e300;
  std::vector<BoxMax> box_max_;
  bool recompute_box(std::int32_t k);
  void recompute_all_boxes();
  void greedy_start();
  // Stage 0 where most points share one death line (floor PD1s): the programme's optimal matching
  // of those points (sorted_birth_seed.hpp), the off-line points free, with potentials certified
  // over every pair; false (and no flow) when they cannot be had.
  bool line_start(const LineAlignment& alignment);
  bool lower_potentials();       // label-correcting sweeps on the candidates; false: negative cycle
  bool lower_until_certified();  // check every pair, add the violated arcs, lower again
  void reset_flow();
  static constexpr std::uint32_t kBand = 32;  // the programme's first half-width, doubled as needed
  static constexpr std::size_t kMaxBandCells = std::size_t{1} << 26;
  // Under q = 1 a line's potentials need long-range arcs: 3 a row per round took 64+ rounds at
  // 20 000 points, 16 took 21.
  static constexpr std::size_t kLineRounds = 64, kMaxSweeps = 200, kLineTopArcs = 16;
  std::vector<std::uint32_t> sweep_order_;  // units of the sweeps: a lone node, or b_j then its mate
  bool started_ = false;                    // a start (greedy or line) has set the flow
  bool on_line_ = false;
  // Routes the diagonal's remaining units, then every free row; with accept_ratio > 1 it may stop
  // (true) once primal_cost() <= accept_ratio * dual_bound(), the free points on the diagonal.
  bool augment_all(double accept_ratio = 1);
  void lower_free_rows();  // each free row's potential to the least feasible value
  // Approximate solves: the free rows lowered, whether finish(accept_ratio * dual bound) found a
  // matching that costs no more (finish: complete_free_rows or match_free_points_apart).
  bool finished_within(double accept_ratio, bool (DiagonalFlow::*finish)(double));
  // The loose points (free, or on the diagonal) matched among themselves and the diagonal,
  // optimally (a solve of their own), the flow's pairs kept; taken (true) when the whole matching
  // then costs <= target. After the line start, whose pairs match the line's points optimally among
  // themselves, this matching costs 0.1-3.3 % more than the optimum on the LAMMPS PD1 pairs for
  // W1, 1.8-17 % (sums of squares) for W2. Ends an approximate solve, as complete_free_rows() does.
  bool match_free_points_apart(double target);
  // A matching from the flow: free rows on the diagonal or, where cheaper, on a candidate whose
  // partner goes to the diagonal (the flow untouched when it costs <= target as it is); taken
  // (true) when it costs <= target. Ends an approximate solve:
  // the flow is no longer one the searches can go on from.
  bool complete_free_rows(double target);

  // Stage 1: the candidate arcs per row, CSR (row i's heads are cand_[cand_start_[i] ..
  // cand_start_[i + 1]]); extra arcs are merged in by add_candidates().
  // The programme's pairs and the nearest neighbours (off_line_only: of the off-line points only).
  void build_candidates(const LineAlignment& alignment, bool off_line_only);
  void add_nearest_candidates(std::optional<double> skip_line);  // skip the points on that line
  void add_candidates(std::span<const std::pair<std::uint32_t, std::uint32_t>> arcs);
  // Stage 2: per row a_i the most negative reduced cost of a pair arc, over every pair; rows
  // beyond rounding are listed in violations_, the rest summed into pair_penalty_ (subtracted by
  // dual_bound(): the LP dual made feasible by raising those rows' potentials).
  struct Violation {
    std::uint32_t row, column;
    double amount;  // -(reduced cost) > 0
  };
  // top_arcs: the most violated arcs listed per row (repair rounds: 3, measured: 1 needs twice the
  // rounds, 6 no fewer; the line start's lowering: kLineTopArcs, where each row may need many).
  void check_pairs(std::size_t top_arcs = 3);
  // Into top, ascending: the count smallest c_ij - pi(b_j) below limit over row i's pair arcs
  // (those that beat sending both to the diagonal), with their columns; found with the 2-d tree.
  void cheapest_pair_prices(std::uint32_t i, std::size_t count, double limit,
                            std::vector<std::pair<double, std::uint32_t>>& top);
  void repair_violations();  // raise each violating row's potential to feasible and free it
  bool sparse_ = false;
  std::vector<std::uint32_t> cand_start_, cand_;
  std::vector<Violation> violations_;
  double pair_penalty_ = 0;
  std::size_t rounds_ = 0, repaired_ = 0;
  bool completed_ = false;
  std::unique_ptr<LinfKdTree> tree_a_;
  std::vector<std::int32_t> box_stack_;
  std::vector<double> box_db_;                     // max db over the box
  std::vector<std::uint32_t> box_run_, box_done_;  // points settled in the box during search box_run_
  std::vector<std::int32_t> box_parent_, leaf_of_b_;
  struct BoxEntry {
    std::uint32_t row;
    std::int32_t node;
  };
  std::vector<BoxEntry> boxes_;  // box heap entries index this
  double current_ = 0;           // key of the entry being processed
  std::int64_t early_ = -1;      // a sink relaxed at distance current_

  // Dijkstra workspace.
  std::uint32_t run_ = 0;
  std::vector<double> dist_, pred_cost_;
  std::vector<std::uint32_t> pred_, seen_, final_;
  std::vector<std::uint32_t> finalized_, path_;
  MonotoneHeap heap_;
  std::size_t augmentations_ = 0, settled_ = 0, boxes_opened_ = 0;
};

}  // namespace fnet
