#include "common/distance/candidate_arcs.hpp"

#include <algorithm>

namespace fnet {

void CandidateArcs::add(std::span<const std::pair<std::uint32_t, std::uint32_t>> arcs) {
  const auto n = static_cast<std::uint32_t>(start_.size() - 1);
  std::vector<std::uint32_t> count(n + 1, 0);
  for (std::uint32_t i = 0; i < n; ++i) count[i] = start_[i + 1] - start_[i];
  for (const auto& [i, j] : arcs) ++count[i];
  std::vector<std::uint32_t> start(n + 1, 0);
  for (std::uint32_t i = 0; i < n; ++i) start[i + 1] = start[i] + count[i];
  std::vector<std::uint32_t> heads(start[n]);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t k = start_[i]; k < start_[i + 1]; ++k) heads[fill[i]++] = heads_[k];
  for (const auto& [i, j] : arcs) heads[fill[i]++] = j;
  // Sort and deduplicate each row in place, then compact.
  heads_.clear();
  heads_.reserve(heads.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto first = heads.begin() + start[i], last = heads.begin() + start[i + 1];
    std::sort(first, last);
    const auto end = std::unique(first, last);
    start_[i] = static_cast<std::uint32_t>(heads_.size());
    heads_.insert(heads_.end(), first, end);
  }
  start_[n] = static_cast<std::uint32_t>(heads_.size());
}

PairArcs nearest_arcs(std::span<const PlanePoint> a, std::span<const PlanePoint> b, const LinfKdTree& tree_a,
                      const LinfKdTree& tree_b, std::size_t count, double scale, std::optional<double> skip_line) {
  PairArcs arcs;
  std::vector<std::uint32_t> near;
  for (std::uint32_t i = 0; i < a.size(); ++i) {
    if (skip_line && a[i].y == *skip_line) continue;
    tree_b.nearest({a[i].x * scale, a[i].y * scale}, count, near, i);
    for (const std::uint32_t j : near) arcs.push_back({i, j});
  }
  for (std::uint32_t j = 0; j < b.size(); ++j) {
    if (skip_line && b[j].y == *skip_line) continue;
    tree_a.nearest({b[j].x / scale, b[j].y / scale}, count, near, j);
    for (const std::uint32_t i : near) arcs.push_back({i, j});
  }
  return arcs;
}

}  // namespace fnet
