// A primal network simplex for the Wasserstein transport on a sparse graph (the diagonal as two
// hubs, as in flow_state.hpp):
//   a_i -> HB cost da_i, HA -> b_j cost db_j, HA -> HB cost 0, and the pair arcs a_i -> b_j given.
// Supplies a_i 1, HA m; demands b_j 1, HB n (or counts per point, see the constructors). Every arc is uncapacitated: a
// transportation problem (sources a_i and HA, sinks b_j and HB), so a flow is integral and a basis is a spanning tree.
// Nodes are numbered as in FlowState: a_0..a_{n-1}, b_0..b_{m-1}, HA = n + m, HB = n + m + 1.
//
// The basis is a spanning tree rooted at HB, stored as parent, pred (the arc to the parent) and its
// direction, the preorder thread (a circular list, with its reverse) and subtree sizes. Invariants:
//  - every non-tree arc carries 0; the tree arcs carry the unique flow that meets the supplies;
//  - potentials: every tree arc u -> v has cost + pi(u) - pi(v) == 0 (to rounding), pi(HB) == 0;
//  - strongly feasible: from every node a positive amount can be sent to the root along the tree
//    (a tree arc carrying 0 points towards the root). The start (every point on the diagonal, HA ->
//    HB carrying 0) is, and the leaving-arc rule below keeps it, so degenerate pivots cannot cycle.
// Pivots: the entering arc is the most negative reduced cost cost + pi(u) - pi(v) within a block
// (0.3 sqrt of the arcs' number) of a pool that holds every improving arc: after a pivot only arcs
// with one end in the moved subtree changed, and of those only the ones its potential shift can
// have lowered (into it when raised, out of it when lowered) are looked at again. The leaving arc
// is the last blocking arc of the cycle met from its apex in the direction of flow. The subtree
// that moves is re-threaded by one pass over it (its potentials move by one amount).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace fnet {

class NetworkSimplex {
 public:
  struct PairStart {
    std::uint32_t i, j;
    double cost;
  };

  // Starts from every point on the diagonal: a_i -> HB and HA -> b_j carry 1, HA -> HB 0.
  NetworkSimplex(std::span<const double> da, std::span<const double> db);
  // The same with points that stand for several (count_a[i] at a_i, count_b[j] at b_j, each >= 1,
  // at most 2^31 - 1 in all per side): a_i -> HB carries count_a[i], HA -> b_j count_b[j].
  NetworkSimplex(std::span<const double> da, std::span<const double> db, std::span<const std::uint32_t> count_a,
                 std::span<const std::uint32_t> count_b);

  // Starts from a matching instead: pairs (i, j, cost), each i and each j at most once, become
  // tree arcs carrying 1 (b_j hanging from a_i, a_i -> HB carrying 0); every other point on the
  // diagonal. Strongly feasible as well. The pairs are the graph's first pair arcs.
  NetworkSimplex(std::span<const double> da, std::span<const double> db, std::span<const PairStart> pairs);

  // A pair arc a_i -> b_j carrying 0 (off the tree): the basis stays valid, and optimal only until
  // its reduced cost is checked by solve(). The caller adds each pair at most once.
  void add_pair_arc(std::uint32_t i, std::uint32_t j, double cost);

  // Pricing by plain block search instead of the pool: the most negative reduced cost within each
  // block of sqrt(arcs) arcs, cyclically over all of them. For dense graphs, where a pivot moves
  // subtrees whose arcs are most of the graph and the pool would be rebuilt at every pivot.
  void price_by_blocks() { by_blocks_ = true; }

  // Pivots until no arc has a reduced cost below rounding (kRelativeTolerance); the potentials are then recomputed
  // from the tree (rounding of the pivots' updates dropped) and checked again. Calls
  // check_work_deadline() once per pivot.
  void solve();

  // The matching the flow is: j >= 0 for a pair, -1 when a_i (or b_j) goes to the diagonal.
  std::vector<std::int64_t> mates_of_a() const;
  // The pair arcs that carry flow, with their amounts (what the counts' constructor's flow is).
  struct PairFlow {
    std::uint32_t i, j, amount;
  };
  std::vector<PairFlow> pair_flows() const;
  std::span<const double> potentials() const { return pi_; }
  // An arc enters when its reduced cost is below -kRelativeTolerance times the sum of its terms'
  // magnitudes (cost and both potentials: a few ulps of them), so that rounding in the potentials
  // cannot make arcs of a tree's cycle look improving, whatever the scale of the costs. Stricter
  // than the certificate's tolerance (DiagonalFlowParams::violation_tolerance), so that what the
  // simplex leaves the certificate does not flag.
  static constexpr double kRelativeTolerance = 0x1p-50;
  std::size_t pivots() const { return pivots_; }
  std::size_t degenerate_pivots() const { return degenerate_; }
  std::size_t pair_arcs() const { return arcs_.size() - first_pair_arc_; }
  // Pricing work: reduced costs looked at (pool, refreshes and full scans), full scans.
  std::size_t reduced_costs_looked_at() const { return scanned_total_; }
  std::size_t full_scans() const { return rebuilds_; }
  std::uint32_t node_count() const { return static_cast<std::uint32_t>(parent_.size()); }

  // Checks every invariant above but strong feasibility (tests): the tree spans the nodes, the
  // thread is its preorder, sizes and flows are right and tree arcs have reduced cost ~0.
  bool consistent() const;

 private:
  struct Arc {
    std::uint32_t from, to;
    double cost;
  };
  double reduced_cost(std::uint32_t e) const { return arcs_[e].cost + pi_[arcs_[e].from] - pi_[arcs_[e].to]; }
  bool improving(std::uint32_t e) const;  // off the tree, reduced cost below rounding
  // Block search over the pool of improving arcs; -1 when the pool holds none.
  std::int64_t find_entering();
  std::int64_t find_entering_by_blocks();  // -1 when no arc is improving
  void build_incidence();
  void rebuild_pool();  // every improving arc, by a scan of all
  void refresh_pool();  // after a pivot: the arcs at the moved subtree's nodes
  void pivot(std::uint32_t entering);
  // Moves the subtree rooted at u_out under v_in, re-rooted at u_in, with the entering arc as
  // u_in's tree arc; sigma added to its potentials.
  void move_subtree(std::uint32_t u_out, std::uint32_t u_in, std::uint32_t v_in, std::uint32_t entering,
                    std::uint32_t join, double sigma);
  void recompute_potentials();
  void link_thread(std::span<const std::uint32_t> order);  // the thread through order, circular

  std::uint32_t n_, m_, root_;
  std::vector<std::int64_t> supply_;  // per node: what leaves it minus what enters, in any flow
  std::vector<Arc> arcs_;
  std::vector<std::int32_t> flow_;
  std::vector<std::uint8_t> in_tree_;
  std::size_t first_pair_arc_;

  std::vector<std::int32_t> parent_;   // -1 at the root
  std::vector<std::uint32_t> pred_;    // the tree arc to the parent
  std::vector<std::uint8_t> up_;       // pred points from the node to its parent
  std::vector<std::uint32_t> thread_;  // preorder successor (circular)
  std::vector<std::uint32_t> rev_thread_;
  std::vector<std::uint32_t> size_;  // subtree sizes
  std::vector<double> pi_;

  std::size_t next_in_pool_ = 0, pivots_ = 0, degenerate_ = 0;
  bool by_blocks_ = false;
  std::size_t next_arc_ = 0;  // block search's cursor
  // Pricing: the pool holds every arc off the tree whose reduced cost was improving when last
  // looked at (a superset of the improving arcs: a pivot changes only the reduced costs of arcs
  // with one end in the moved subtree, and those are looked at again after it).
  std::vector<std::uint32_t> pool_;
  std::vector<std::uint8_t> in_pool_;
  std::vector<std::uint32_t> incidence_start_, incidence_;  // per a_i, b_j: the arcs at it
  static constexpr double kBlockFactor = 0.3;
  double last_sigma_ = 0;  // the moved subtree's potential change in the last pivot
  std::size_t scanned_total_ = 0, rebuilds_ = 0;
  std::vector<std::uint32_t> moved_, order_, stem_, position_;  // scratch of move_subtree
};

}  // namespace fnet
