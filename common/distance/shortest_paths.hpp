// The successive-shortest-path runner: Dijkstra with potentials on the residual graph of the flow,
// by reduced costs, with an early exit at the first sink, then one unit augmented along the path.
// Its heap is a radix heap (monotone_heap.hpp). The hubs' arcs are offered lazily, in key order,
// one heap entry per stream at a time (hub_arcs.hpp). Pair arcs come from one of two sources:
//  - sparse: each row's candidate arcs (candidate_arcs.hpp) only;
//  - complete: when a_i is settled it enters the 2-d tree over B (its home leaf, then the sibling
//    of each box on the way to the root) as heap entries keyed by a lower bound on the reduced cost
//    of any arc into the box (pair_oracle.hpp). Boxes are opened best first, boxes whose points are
//    all settled are skipped, so the search is exact on the complete graph.
// After a search each settled node's potential is lowered by its distance's shortfall to the
// sink's and the rest are kept, so the arcs the searches scan keep reduced costs >= 0 (rounding
// below 0 is clamped in the keys).
#pragma once

#include <cstdint>
#include <vector>

#include "common/distance/candidate_arcs.hpp"
#include "common/distance/flow_state.hpp"
#include "common/distance/hub_arcs.hpp"
#include "common/distance/monotone_heap.hpp"
#include "common/distance/pair_oracle.hpp"

namespace fnet {

class ShortestPaths {
 public:
  ShortestPaths(FlowState& flow, HubArcs& hubs, PairOracle& oracle, const CandidateArcs& candidates);

  // sparse: scan the candidate arcs; otherwise the complete graph through the tree's boxes, whose
  // maxima the runner then keeps up to date.
  void set_sparse(bool sparse) { sparse_ = sparse; }

  // A shortest path from source to a sink, then augment; false when no sink is reachable.
  bool route(std::uint32_t source);

  std::size_t augmentations() const { return augmentations_; }
  std::size_t settled() const { return settled_; }
  std::size_t boxes_opened() const { return boxes_opened_; }

 private:
  // Heap entries, ordered by (key, id): a node (its id), a hub's lazy arc stream (negative), or a
  // tree box entered for a row (kBoxBase + its index in boxes_). At equal keys streams pop first,
  // then nodes, then boxes: a sink found at the current distance ends the search before any box
  // that cannot beat it is opened.
  static constexpr std::int64_t kBoxBase = std::int64_t{1} << 40;
  static std::int64_t stream_entry(int stream) { return -1 - stream; }
  static bool is_stream_entry(std::int64_t id) { return id < 0; }
  static int stream_of_entry(std::int64_t id) { return static_cast<int>(-1 - id); }
  static bool is_box_entry(std::int64_t id) { return id >= kBoxBase; }
  void push(double key, std::int64_t id) { heap_.push({key, id}); }
  void push_box(std::uint32_t row, std::int32_t node, double key);

  void augment(std::uint32_t source, std::uint32_t target);
  void relax(std::uint32_t v, double d, std::uint32_t from, double cost);
  void scan(std::uint32_t u, double d);
  void scan_boxes(std::uint32_t u, double d);  // a_u's pair arcs on the complete graph
  bool skip_settled(int stream);               // walks past settled heads; false at the end
  void push_stream(int stream);                // files the stream's next arc in the heap
  void start_stream(int stream, double d);     // the hub is settled at distance d
  void pop_stream(int stream);                 // relaxes the stream's next arc
  double box_key(std::uint32_t i, std::int32_t node) const;
  void open_box(std::uint32_t i, std::int32_t node);

  FlowState& flow_;
  HubArcs& hubs_;
  PairOracle& oracle_;
  const CandidateArcs& candidates_;
  bool sparse_ = false;

  double hub_dist_[2] = {0, 0};  // per stream: the distance of its hub
  struct BoxEntry {
    std::uint32_t row;
    std::int32_t node;
  };
  std::vector<BoxEntry> boxes_;                    // box heap entries index this
  std::vector<std::uint32_t> box_run_, box_done_;  // points settled in the box during search box_run_
  std::vector<std::int32_t> box_stack_;
  double current_ = 0;       // key of the entry being processed
  std::int64_t early_ = -1;  // a sink relaxed at distance current_

  std::uint32_t run_ = 0;
  std::vector<double> dist_, pred_cost_;
  std::vector<std::uint32_t> pred_, seen_, final_;
  std::vector<std::uint32_t> finalized_, path_;
  MonotoneHeap heap_;
  std::size_t augmentations_ = 0, settled_ = 0, boxes_opened_ = 0;
};

}  // namespace fnet
