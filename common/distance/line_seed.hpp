// A starting matching and candidate pairs from the death lines: under `floor` most of a force
// network's PD1 lies on one line death = 0 (classes that never die), and diagrams stacked or
// offset may hold several such lines. On each line shared by both sides with at least
// `min_points` points on each, the sorted-birth programme (sorted_birth_seed.hpp) finds the
// optimal matching of that line's points among themselves (its band doubling until it holds the
// optimum, or up to max_cells cells); its pairs that beat the diagonal are the start, its pairs
// and their neighbours in rank (the
// partner's `ranks` columns either side) are candidates. That catches what nearest neighbours miss when a
// whole line stretches (partners hundreds of ranks apart). Exactness never depends on it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/distance/candidate_arcs.hpp"
#include "common/distance/flow_state.hpp"

namespace fnet {

struct LineSeed {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // a matching: each i, each j at most once
  PairArcs candidates;
};

// ranks: candidates also pair each line row with the `ranks` columns either side of its partner.
LineSeed line_seed(const FlowState& flow, std::uint32_t band, std::size_t max_cells, std::size_t min_points,
                   std::uint32_t ranks);

}  // namespace fnet
