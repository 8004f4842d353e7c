// The pair arcs the sparse searches scan, per row a_i: its heads b_j, ascending, each once (in
// one array, row after row). A value type: arcs are only ever added.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "common/distance/linf_kdtree.hpp"

namespace fnet {

using PairArcs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;  // (i, j), repeats allowed

class CandidateArcs {
 public:
  explicit CandidateArcs(std::uint32_t rows = 0) : start_(rows + 1, 0) {}

  std::span<const std::uint32_t> row(std::uint32_t i) const {
    return std::span(heads_).subspan(start_[i], start_[i + 1] - start_[i]);
  }
  std::size_t size() const { return heads_.size(); }

  // Merges arcs in (each row sorted and deduplicated again).
  void add(std::span<const std::pair<std::uint32_t, std::uint32_t>> arcs);

 private:
  std::vector<std::uint32_t> start_, heads_;
};

// Each point's `count` nearest neighbours on the other side (a over tree_b, b over tree_a, ties
// spread by the point's index), that side brought to the scale of the other first (births and
// deaths times scale for a, divided by it for b); points on the death line skip_line left out.
PairArcs nearest_arcs(std::span<const PlanePoint> a, std::span<const PlanePoint> b, const LinfKdTree& tree_a,
                      const LinfKdTree& tree_b, std::size_t count, double scale, std::optional<double> skip_line);

}  // namespace fnet
