#include "common/analysis/blocks.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

#include "common/topology/force_network.hpp"
#include "common/topology/persistence.hpp"

namespace fnet {
namespace {

// The k + 1 edges of a grid's columns (or rows) over [lo, hi]; the last is hi exactly, so that
// the reported bounds of neighbouring cells share their edge bit for bit.
std::vector<double> grid_edges(double lo, double hi, int k) {
  std::vector<double> edges(static_cast<std::size_t>(k) + 1);
  for (int c = 0; c < k; ++c) edges[c] = lo + (hi - lo) * c / k;
  edges[k] = hi;
  return edges;
}

// The column holding coordinate v: the number of inner edges at or below it, so that a point on
// an edge goes to the larger index. A domain of zero extent has the one column 0.
int column_of(const std::vector<double>& edges, double v) {
  const int k = static_cast<int>(edges.size()) - 1;
  if (edges.front() == edges.back()) return 0;
  const auto inner_end = edges.end() - 1;
  return std::clamp(static_cast<int>(std::upper_bound(edges.begin() + 1, inner_end, v) - (edges.begin() + 1)), 0,
                    k - 1);
}

// The contact point of grains a and b: on the line of centres at distance a.r from a's centre (a's
// centre itself when the centres coincide). 2D frames take the planar formula, so that their cells
// do not depend on how a z of 0 would round.
std::tuple<double, double, double> contact_point(const Particle& a, const Particle& b, int dimension) {
  const double dx = b.x - a.x, dy = b.y - a.y, dz = dimension == 3 ? b.z - a.z : 0.0;
  const double len = dimension == 3 ? std::hypot(dx, dy, dz) : std::hypot(dx, dy);
  if (!(len > 0)) return {a.x, a.y, a.z};
  return {a.x + a.r * dx / len, a.y + a.r * dy / len, a.z + a.r * dz / len};
}

}  // namespace

BlockDomain block_domain(const Frame& frame) {
  if (frame.particles.empty() || frame.particles.size() != frame.particle_count)
    throw std::invalid_argument(frame.label + ": blocks need every grain's position (the frame has " +
                                std::to_string(frame.particles.size()) + " of " + std::to_string(frame.particle_count) +
                                ")");
  BlockDomain d{INFINITY, -INFINITY, INFINITY, -INFINITY, 0, 0};
  for (const Particle& p : frame.particles) {
    d.x_lo = std::min(d.x_lo, p.x - p.r), d.x_hi = std::max(d.x_hi, p.x + p.r);
    d.y_lo = std::min(d.y_lo, p.y - p.r), d.y_hi = std::max(d.y_hi, p.y + p.r);
  }
  if (frame.dimension == 3) {
    d.z_lo = INFINITY, d.z_hi = -INFINITY;
    for (const Particle& p : frame.particles)
      d.z_lo = std::min(d.z_lo, p.z - p.r), d.z_hi = std::max(d.z_hi, p.z + p.r);
  }
  return d;
}

std::vector<BlockCell> split_into_blocks(const Frame& frame, int k) {
  if (k < kMinBlocks || k > kMaxBlocks)
    throw std::invalid_argument("k must be an integer from " + std::to_string(kMinBlocks) + " to " +
                                std::to_string(kMaxBlocks) + " (got " + std::to_string(k) + ")");
  const BlockDomain d = block_domain(frame);
  const int layers = frame.dimension == 3 ? k : 1;
  const std::vector<double> xs = grid_edges(d.x_lo, d.x_hi, k), ys = grid_edges(d.y_lo, d.y_hi, k),
                            zs = grid_edges(d.z_lo, d.z_hi, layers);
  std::vector<BlockCell> cells(static_cast<std::size_t>(layers) * k * k);
  for (int layer = 0; layer < layers; ++layer)
    for (int row = 0; row < k; ++row)
      for (int col = 0; col < k; ++col) {
        BlockCell& c = cells[(layer * k + row) * k + col];
        c.layer = layer, c.row = row, c.col = col;
        c.bounds = {xs[col], xs[col + 1], ys[row], ys[row + 1], zs[layer], zs[layer + 1]};
      }
  const auto cell_at = [&](double x, double y, double z) -> BlockCell& {
    return cells[(column_of(zs, z) * k + column_of(ys, y)) * k + column_of(xs, x)];
  };
  std::vector<bool> touched(frame.particle_count, false);
  for (std::size_t n = 0; n < frame.contacts.size(); ++n) {
    const Contact& c = frame.contacts[n];
    const Particle& a = frame.particles[c.i];
    const Particle& b = frame.particles[c.j];
    BlockCell& cell = std::apply(cell_at, contact_point(a, b, frame.dimension));
    cell.contacts.push_back(n);
    cell.grains.push_back(static_cast<std::uint32_t>(c.i));
    cell.grains.push_back(static_cast<std::uint32_t>(c.j));
    touched[c.i] = touched[c.j] = true;
  }
  for (std::size_t g = 0; g < frame.particle_count; ++g)
    if (!touched[g])
      cell_at(frame.particles[g].x, frame.particles[g].y, frame.particles[g].z)
          .grains.push_back(static_cast<std::uint32_t>(g));
  std::vector<std::uint32_t> renumbered(frame.particle_count);
  for (BlockCell& cell : cells) {
    std::sort(cell.grains.begin(), cell.grains.end());
    cell.grains.erase(std::unique(cell.grains.begin(), cell.grains.end()), cell.grains.end());
    Frame& net = cell.network;
    std::string index = std::to_string(cell.row) + ", " + std::to_string(cell.col);
    if (frame.dimension == 3) index = std::to_string(cell.layer) + ", " + index;
    net.label = frame.label + " cell (" + index + ")";
    net.dimension = frame.dimension;
    net.particle_count = cell.grains.size();
    net.particles.reserve(cell.grains.size());
    for (std::size_t g = 0; g < cell.grains.size(); ++g) {
      renumbered[cell.grains[g]] = static_cast<std::uint32_t>(g);
      net.particles.push_back(frame.particles[cell.grains[g]]);
    }
    net.contacts.reserve(cell.contacts.size());
    for (const std::size_t n : cell.contacts) {
      Contact c = frame.contacts[n];
      c.i = renumbered[c.i], c.j = renumbered[c.j];
      net.contacts.push_back(c);
    }
  }
  return cells;
}

FrameDiagrams block_diagrams(const BlockCell& cell, ForceKind force) {
  return compute_persistence(build_network(cell.network, force));
}

std::vector<BlockDistance> block_distances(const std::vector<BlockCell>& a, const std::vector<BlockCell>& b,
                                           DistanceMetric metric, int dim, ForceKind force,
                                           EssentialConvention essential) {
  if (a.size() != b.size())
    throw std::invalid_argument("block grids differ: " + std::to_string(a.size()) + " vs " + std::to_string(b.size()) +
                                " cells");
  std::vector<BlockDistance> out;
  out.reserve(a.size());
  for (std::size_t c = 0; c < a.size(); ++c) {
    const FrameDiagrams da = block_diagrams(a[c], force), db = block_diagrams(b[c], force);
    const Diagram& pa = dim == 0 ? da.pd0 : da.pd1;
    const Diagram& pb = dim == 0 ? db.pd0 : db.pd1;
    out.push_back({diagram_distance(pa, pb, metric, essential), pa.size(), pb.size()});
  }
  return out;
}

}  // namespace fnet
