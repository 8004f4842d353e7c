// The hubs' many arcs as two lazy streams, walked in key order by the searches so that a search
// costs what it visits, not O(n + m): HA -> b_j for every b_j not fed by HA, keyed db_j - pi(b_j);
// HB -> a_i for every a_i sent to the diagonal, keyed -da_i - pi(a_i). A stream's reduced cost is
// pi(hub) + key. Invariant: refresh(v) follows every change of v's mate or potential before the
// next search (the hubs themselves are never filed).
#pragma once

#include <cstdint>

#include "common/distance/flow_state.hpp"
#include "common/distance/keyed_index.hpp"

namespace fnet {

class HubArcs {
 public:
  enum Stream : int { kFromHa = 0, kFromHb = 1 };

  // HA's stream holds every b_j (nothing is fed from the diagonal yet); HB's is empty.
  explicit HubArcs(const FlowState& flow) : from_ha_(flow.m), from_hb_(flow.n) {
    for (std::uint32_t j = 0; j < flow.m; ++j) refresh(flow, flow.node_of_b(j));
  }

  void refresh(const FlowState& flow, std::uint32_t node) {
    if (flow.is_a(node)) {
      if (flow.mate_a[node] == FlowState::kDiagonal) {
        from_hb_.set(node, -flow.da[node] - flow.pi[node]);
      } else {
        from_hb_.erase(node);
      }
    } else if (flow.is_b(node)) {
      const std::uint32_t j = flow.b_of_node(node);
      if (flow.mate_b[j] != FlowState::kDiagonal) {
        from_ha_.set(j, flow.db[j] - flow.pi[node]);
      } else {
        from_ha_.erase(j);
      }
    }
  }
  void refresh_points(const FlowState& flow) {
    for (std::uint32_t v = 0; v < flow.n + flow.m; ++v) refresh(flow, v);
  }

  // The stream's (key, index of b_j or a_i) entries, its hub and the node an index stands for.
  KeyedIndex& arcs(int stream) { return stream == kFromHa ? from_ha_ : from_hb_; }
  static std::uint32_t hub(const FlowState& flow, int stream) { return stream == kFromHa ? flow.ha : flow.hb; }
  static std::uint32_t node(const FlowState& flow, int stream, std::uint32_t index) {
    return stream == kFromHa ? flow.node_of_b(index) : index;
  }
  // The cost of the stream's arc into that node: db_j in, or -da_i (the unit leaves the diagonal).
  static double arc_cost(const FlowState& flow, int stream, std::uint32_t index) {
    return stream == kFromHa ? flow.db[index] : -flow.da[index];
  }

 private:
  KeyedIndex from_ha_, from_hb_;
};

}  // namespace fnet
