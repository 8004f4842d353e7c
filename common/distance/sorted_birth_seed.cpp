#include "common/distance/sorted_birth_seed.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>

#include "common/distance/infinity.hpp"

namespace fnet {

namespace {
// The points on the line death = y, by birth.
std::vector<std::uint32_t> by_birth(std::span<const PlanePoint> p, double y) {
  std::vector<std::uint32_t> order;
  for (std::uint32_t i = 0; i < p.size(); ++i)
    if (p[i].y == y) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t u, std::uint32_t v) { return p[u].x < p[v].x; });
  return order;
}

// The death value most points share (floor: the floor itself).
double common_death(std::span<const PlanePoint> a, std::span<const PlanePoint> b) {
  std::vector<double> y;
  y.reserve(a.size() + b.size());
  for (const auto* side : {&a, &b})
    for (const PlanePoint p : *side) y.push_back(p.y);
  std::sort(y.begin(), y.end());
  double best = y.front();
  std::size_t run = 0, best_run = 0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    run = k > 0 && y[k] == y[k - 1] ? run + 1 : 1;
    if (run > best_run) best_run = run, best = y[k];
  }
  return best;
}
enum Step : std::uint8_t { kPair, kDeleteA, kDeleteB, kOutside };
}  // namespace

double quantile_scale(std::span<const PlanePoint> a, std::span<const PlanePoint> b) {
  if (a.empty() || b.empty()) return 1;
  std::vector<double> xa, xb;
  for (const PlanePoint p : a) xa.push_back(p.x);
  for (const PlanePoint p : b) xb.push_back(p.x);
  std::sort(xa.begin(), xa.end());
  std::sort(xb.begin(), xb.end());
  std::vector<double> ratios;
  for (std::size_t k = xa.size() / 10; k < xa.size() * 9 / 10; ++k) {
    const double y = xb[k * xb.size() / xa.size()];
    if (xa[k] != 0) ratios.push_back(y / xa[k]);
  }
  if (ratios.empty()) return 1;
  std::nth_element(ratios.begin(), ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2), ratios.end());
  const double f = ratios[ratios.size() / 2];
  return f > 0 && std::isfinite(f) ? f : 1;
}

double share_on_common_line(std::span<const PlanePoint> a, std::span<const PlanePoint> b) {
  if (a.empty() && b.empty()) return 0;
  const double line = common_death(a, b);
  std::size_t on = 0;
  for (const auto* side : {&a, &b})
    for (const PlanePoint p : *side) on += p.y == line;
  return static_cast<double>(on) / static_cast<double>(a.size() + b.size());
}

LineAlignment sorted_birth_alignment(std::span<const PlanePoint> a, std::span<const PlanePoint> b,
                                     std::span<const double> da, std::span<const double> db,
                                     const std::function<double(std::uint32_t, std::uint32_t)>& cost,
                                     std::uint32_t half_width) {
  LineAlignment out;
  if (a.empty() || b.empty()) return out;
  const double line = common_death(a, b);
  out.line = line;
  out.order_a = by_birth(a, line), out.order_b = by_birth(b, line);
  const std::vector<std::uint32_t>&oa = out.order_a, &ob = out.order_b;
  const std::size_t n = oa.size(), m = ob.size();
  if (n == 0 || m == 0) return out;
  const std::int64_t w = static_cast<std::int64_t>(half_width) +
                         (n > m ? static_cast<std::int64_t>(n - m) : static_cast<std::int64_t>(m - n));
  // Row i (0..n, i points of A consumed) covers columns [lo(i), hi(i)] of 0..m.
  const auto center = [&](std::size_t i) { return static_cast<std::int64_t>(i * m / n); };
  const auto lo = [&](std::size_t i) { return std::max<std::int64_t>(0, center(i) - w); };
  const auto hi = [&](std::size_t i) { return std::min<std::int64_t>(static_cast<std::int64_t>(m), center(i) + w); };
  const std::size_t width = static_cast<std::size_t>(2 * w + 1);
  std::vector<double> prev(m + 1, kInf), cur(m + 1, kInf);
  std::vector<std::uint8_t> step((n + 1) * width, kOutside);
  const auto at = [&](std::size_t i, std::int64_t j) { return i * width + static_cast<std::size_t>(j - lo(i)); };
  prev[0] = 0;
  for (std::int64_t j = 1; j <= hi(0); ++j) prev[j] = prev[j - 1] + db[ob[j - 1]], step[at(0, j)] = kDeleteB;
  for (std::size_t i = 1; i <= n; ++i) {
    const std::int64_t l = lo(i), h = hi(i);
    const double dai = da[oa[i - 1]];
    // prev holds row i - 1 on [lo(i-1), hi(i-1)] and is infinite elsewhere.
    for (std::int64_t j = l; j <= h; ++j) {
      double best = j <= hi(i - 1) && j >= lo(i - 1) ? prev[j] + dai : kInf;
      std::uint8_t s = kDeleteA;
      if (j > l && cur[j - 1] + db[ob[j - 1]] < best) best = cur[j - 1] + db[ob[j - 1]], s = kDeleteB;
      if (j > 0 && j - 1 >= lo(i - 1) && j - 1 <= hi(i - 1)) {
        const std::uint32_t u = oa[i - 1], v = ob[j - 1];
        const double pair = prev[j - 1] + std::min(cost(u, v), dai + db[v]);
        if (pair <= best) best = pair, s = kPair;
      }
      cur[j] = best;
      step[at(i, j)] = best < kInf ? s : std::uint8_t{kOutside};
    }
    for (std::int64_t j = lo(i - 1); j <= hi(i - 1); ++j)
      if (j < l || j > h) prev[j] = kInf;
    for (std::int64_t j = l; j <= h; ++j) prev[j] = cur[j], cur[j] = kInf;
  }
  // Walk back from (n, m); when the band does not reach it, from the nearest cell of the last row
  // (the columns beyond are then sent to the diagonal, and the alignment is not optimal).
  std::size_t i = n;
  std::int64_t j = static_cast<std::int64_t>(m);
  out.optimal = hi(n) == j;
  for (; j > hi(n); --j)
    out.moves.push_back(
        {LineAlignment::Step::delete_b, static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(j - 1)});
  while (i > 0 || j > 0) {
    const std::uint8_t s = (j >= lo(i) && j <= hi(i)) ? step[at(i, j)] : std::uint8_t{kOutside};
    // A path along the band's edge may have been cut off by it: not known optimal.
    if (s == kOutside || (j == lo(i) && j > 0) || (j == hi(i) && j < static_cast<std::int64_t>(m))) out.optimal = false;
    const auto r = static_cast<std::uint32_t>(i) - 1, c = static_cast<std::uint32_t>(j) - 1;
    if (s == kPair) {
      out.moves.push_back({LineAlignment::Step::pair, r, c});
      --i, --j;
    } else if (s == kDeleteA || (s == kOutside && i > 0)) {
      out.moves.push_back({LineAlignment::Step::delete_a, r, static_cast<std::uint32_t>(j)});
      --i;
    } else {
      out.moves.push_back({LineAlignment::Step::delete_b, static_cast<std::uint32_t>(i), c});
      --j;
    }
  }
  std::reverse(out.moves.begin(), out.moves.end());
  return out;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted_birth_candidates(
    std::span<const PlanePoint> a, std::span<const PlanePoint> b, std::span<const double> da,
    std::span<const double> db, const std::function<double(std::uint32_t, std::uint32_t)>& cost,
    std::uint32_t half_width) {
  return alignment_candidates(sorted_birth_alignment(a, b, da, db, cost, half_width));
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> alignment_candidates(const LineAlignment& alignment) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  const auto n = static_cast<std::int64_t>(alignment.order_a.size()),
             m = static_cast<std::int64_t>(alignment.order_b.size());
  const auto add = [&](std::int64_t r, std::int64_t c) {
    if (r >= 0 && c >= 0 && r < n && c < m)
      out.push_back({alignment.order_a[static_cast<std::size_t>(r)], alignment.order_b[static_cast<std::size_t>(c)]});
  };
  for (const LineAlignment::Move move : alignment.moves) {
    const std::int64_t r = move.rank_a, c = move.rank_b;
    switch (move.step) {
      case LineAlignment::Step::pair:
        // Off-line points take line partners, shifting the full problem's alignment by a few
        // ranks against the programme's (measured on LAMMPS PD1: up to ~5): +-3 columns.
        for (std::int64_t dc = -3; dc <= 3; ++dc) add(r, c + dc);
        add(r - 1, c), add(r + 1, c);
        break;
      case LineAlignment::Step::delete_a:  // rank_b: the columns consumed so far
        add(r, c - 1), add(r, c);
        break;
      case LineAlignment::Step::delete_b:  // rank_a: the rows consumed so far
        add(r - 1, c), add(r, c);
        break;
    }
  }
  return out;
}

}  // namespace fnet
