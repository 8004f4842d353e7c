#include "server/dem/neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace fnet::sim {

void setup_grid(NeighbourList& list, double lo, double hi, double max_diameter, double skin) {
  list.skin = skin;
  list.grid_lo = lo;
  const double reach = max_diameter + skin;  // farthest centre distance of a listed pair
  const auto cells = static_cast<std::uint32_t>(std::max(1.0, std::floor((hi - lo) / reach)));
  list.cells_per_side = cells;
  list.cell = (hi - lo) / cells;
}

void index_partners(NeighbourList& list, std::size_t bodies) {
  const std::size_t pairs = list.partner.size();
  list.in_offset.assign(bodies + 1, 0);
  for (std::size_t q = 0; q < pairs; ++q) ++list.in_offset[list.partner[q] + 1];
  for (std::size_t b = 0; b < bodies; ++b) list.in_offset[b + 1] += list.in_offset[b];
  list.in_pair.resize(pairs);
  list.old_offset.assign(list.in_offset.begin(), list.in_offset.end() - 1);  // fill cursor (scratch)
  for (std::size_t q = 0; q < pairs; ++q)
    list.in_pair[list.old_offset[list.partner[q]]++] = static_cast<std::uint32_t>(q);
}

void rebuild(NeighbourList& list, std::span<const double> x, std::span<const double> y, std::span<const double> radius,
             std::span<const double> inv_mass, std::size_t n, double wall_offset) {
  const std::size_t bodies = x.size();
  const std::uint32_t side = list.cells_per_side;
  const std::size_t cells = static_cast<std::size_t>(side) * side;
  const double inv_cell = 1.0 / list.cell;

  // Bin every body (counting sort by cell): bodies of a cell stay in index order.
  list.body_cell.resize(bodies);
  list.cell_start.assign(cells + 1, 0);
  for (std::size_t b = 0; b < bodies; ++b) {
    const double fx = (x[b] - list.grid_lo) * inv_cell, fy = (y[b] - list.grid_lo) * inv_cell;
    if (!(fx >= 0 && fy >= 0 && fx < side && fy < side))
      throw std::runtime_error("body " + std::to_string(b) + (b < n ? " (grain)" : " (wall particle)") +
                               " left the simulation domain or is not finite: position (" + std::to_string(x[b]) +
                               ", " + std::to_string(y[b]) + ")");
    const auto c = static_cast<std::uint32_t>(fy) * side + static_cast<std::uint32_t>(fx);
    list.body_cell[b] = c;
    ++list.cell_start[c + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) list.cell_start[c + 1] += list.cell_start[c];
  list.cell_bodies.resize(bodies);
  {
    list.old_offset.assign(list.cell_start.begin(), list.cell_start.end() - 1);  // fill cursor
    for (std::size_t b = 0; b < bodies; ++b)
      list.cell_bodies[list.old_offset[list.body_cell[b]]++] = static_cast<std::uint32_t>(b);
  }

  // Keep the old list for the history transfer.
  std::swap(list.old_offset, list.offset);
  std::swap(list.old_partner, list.partner);
  std::swap(list.old_hx, list.hx);
  std::swap(list.old_hy, list.hy);
  const bool had_list = list.old_offset.size() == n + 1;

  list.offset.resize(n + 1);
  list.partner.clear();
  list.hx.clear();
  list.hy.clear();
  list.offset[0] = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t ci = list.body_cell[i];
    const std::uint32_t cx = ci % side, cy = ci / side;
    const double xi = x[i], yi = y[i], ri = radius[i] + list.skin;
    const std::uint32_t x_lo = cx > 0 ? cx - 1 : 0, x_hi = std::min(cx + 1, side - 1);
    const std::uint32_t y_lo = cy > 0 ? cy - 1 : 0, y_hi = std::min(cy + 1, side - 1);
    const std::size_t first = list.partner.size();
    for (std::uint32_t gy = y_lo; gy <= y_hi; ++gy) {
      for (std::uint32_t gx = x_lo; gx <= x_hi; ++gx) {
        const std::uint32_t c = gy * side + gx;
        for (std::uint32_t k = list.cell_start[c]; k < list.cell_start[c + 1]; ++k) {
          const std::uint32_t j = list.cell_bodies[k];
          if (j <= i) continue;  // grains pair once; walls (j >= n > i) always pass
          const double dx = xi - x[j], dy = yi - y[j], reach = ri + radius[j];
          if (dx * dx + dy * dy < reach * reach) list.partner.push_back(j);
        }
      }
    }
    // Partners in increasing index: deterministic, and the history lookup below is a merge.
    std::sort(list.partner.begin() + static_cast<std::ptrdiff_t>(first), list.partner.end());
    list.offset[i + 1] = static_cast<std::uint32_t>(list.partner.size());
  }

  const std::size_t pairs = list.partner.size();
  list.hx.assign(pairs, 0.0);
  list.hy.assign(pairs, 0.0);
  list.fn.assign(pairs, 0.0);
  list.ft2.assign(pairs, 0.0);
  list.meff.resize(pairs);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t p = list.offset[i]; p < list.offset[i + 1]; ++p)
      list.meff[p] = 1.0 / (inv_mass[i] + inv_mass[list.partner[p]]);
  list.touching.assign(pairs, 0);
  if (had_list) {
    for (std::size_t i = 0; i < n; ++i) {
      std::uint32_t o = list.old_offset[i];
      const std::uint32_t o_end = list.old_offset[i + 1];
      for (std::uint32_t p = list.offset[i]; p < list.offset[i + 1] && o < o_end; ++p) {
        while (o < o_end && list.old_partner[o] < list.partner[p]) ++o;
        if (o < o_end && list.old_partner[o] == list.partner[p]) {
          list.hx[p] = list.old_hx[o];
          list.hy[p] = list.old_hy[o];
        }
      }
    }
  }
  // Touching flags are recomputed by the next force evaluation; a pair with history was touching.
  for (std::size_t p = 0; p < pairs; ++p) list.touching[p] = (list.hx[p] != 0 || list.hy[p] != 0);

  index_partners(list, bodies);

  list.x_build.assign(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n));
  list.y_build.assign(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(n));
  list.wall_offset_build = wall_offset;
  ++list.builds;
}

}  // namespace fnet::sim
