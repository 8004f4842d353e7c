#include "common/distance/line_seed.hpp"

#include <algorithm>

#include "common/distance/sorted_birth_seed.hpp"

namespace fnet {

LineSeed line_seed(const FlowState& flow, std::uint32_t band, std::size_t max_cells, std::size_t min_points,
                   std::uint32_t ranks_wide) {
  const auto ranks = static_cast<std::int64_t>(ranks_wide);
  LineSeed seed;
  // Every point by death value, A's before B's within a value.
  struct Entry {
    double y;
    std::uint32_t side, index;
  };
  std::vector<Entry> entries;
  entries.reserve(flow.n + flow.m);
  for (std::uint32_t i = 0; i < flow.n; ++i) entries.push_back({flow.a[i].y, 0, i});
  for (std::uint32_t j = 0; j < flow.m; ++j) entries.push_back({flow.b[j].y, 1, j});
  std::sort(entries.begin(), entries.end(),
            [](const Entry& u, const Entry& v) { return u.y != v.y ? u.y < v.y : u.side < v.side; });
  std::vector<std::uint32_t> ia, ib;
  std::vector<PlanePoint> pa, pb;
  std::vector<double> da, db;
  for (std::size_t begin = 0; begin < entries.size();) {
    std::size_t end = begin;
    while (end < entries.size() && entries[end].y == entries[begin].y) ++end;
    ia.clear(), ib.clear();
    for (std::size_t k = begin; k < end; ++k) (entries[k].side ? ib : ia).push_back(entries[k].index);
    begin = end;
    if (ia.size() < min_points || ib.size() < min_points) continue;
    pa.clear(), pb.clear(), da.clear(), db.clear();
    for (const std::uint32_t i : ia) pa.push_back(flow.a[i]), da.push_back(flow.da[i]);
    for (const std::uint32_t j : ib) pb.push_back(flow.b[j]), db.push_back(flow.db[j]);
    const auto cost = [&](std::uint32_t u, std::uint32_t v) { return flow.cost(ia[u], ib[v]); };
    const auto size = static_cast<std::uint32_t>(std::max(ia.size(), ib.size()));
    LineAlignment alignment;
    for (std::uint32_t width = band;; width *= 2) {
      alignment = sorted_birth_alignment(pa, pb, da, db, cost, width);
      const std::size_t cells = std::size_t{size} * (4 * std::size_t{width} + 1);
      if (alignment.optimal || width >= size || cells > max_cells) break;
    }
    for (const LineAlignment::Move& move : alignment.moves) {
      if (move.step != LineAlignment::Step::pair) continue;
      const std::uint32_t i = ia[alignment.order_a[move.rank_a]], j = ib[alignment.order_b[move.rank_b]];
      if (flow.cost(i, j) < flow.da[i] + flow.db[j]) seed.pairs.push_back({i, j});
    }
    // Each row's partner and `ranks` columns either side (rows sent to the diagonal: the columns
    // around where they were passed), and the programme's own candidates.
    for (const auto& [u, v] : alignment_candidates(alignment)) seed.candidates.push_back({ia[u], ib[v]});
    const auto columns = static_cast<std::int64_t>(alignment.order_b.size());
    for (const LineAlignment::Move& move : alignment.moves) {
      if (move.step == LineAlignment::Step::delete_b) continue;
      const std::uint32_t i = ia[alignment.order_a[move.rank_a]];
      const auto c = static_cast<std::int64_t>(move.rank_b);
      for (std::int64_t k = std::max<std::int64_t>(0, c - ranks); k <= std::min(columns - 1, c + ranks); ++k)
        seed.candidates.push_back({i, ib[alignment.order_b[static_cast<std::size_t>(k)]]});
    }
  }
  return seed;
}

}  // namespace fnet
