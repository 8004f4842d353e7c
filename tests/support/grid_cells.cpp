#include "tests/support/grid_cells.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace fnet::testing {

std::vector<std::size_t> contacts_in_cell(const Frame& f, int k, int layer, int row, int col, double margin) {
  std::array<std::array<double, 2>, 3> box;
  for (auto& axis : box) axis = {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const Particle& p : f.particles) {
    const double at[3] = {p.x, p.y, p.z};
    for (int axis = 0; axis < 3; ++axis)
      box[axis] = {std::min(box[axis][0], at[axis] - p.r), std::max(box[axis][1], at[axis] + p.r)};
  }
  const int index[3] = {col, row, layer};
  std::vector<std::size_t> out;
  for (std::size_t n = 0; n < f.contacts.size(); ++n) {
    const Particle &a = f.particles[f.contacts[n].i], &b = f.particles[f.contacts[n].j];
    const double d[3] = {b.x - a.x, b.y - a.y, b.z - a.z};
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double point[3] = {a.x + a.r * d[0] / len, a.y + a.r * d[1] / len, a.z + a.r * d[2] / len};
    bool inside = true;
    for (int axis = 0; axis < 3; ++axis) {
      const double width = (box[axis][1] - box[axis][0]) / k;
      const double lo = box[axis][0] + width * index[axis], hi = lo + width;
      inside = inside && point[axis] > lo + margin && point[axis] < hi - margin;
    }
    if (inside) out.push_back(n);
  }
  return out;
}

Frame strengthen(const Frame& frame, const std::vector<std::size_t>& contacts, std::size_t count) {
  Frame out = frame;
  for (std::size_t k = 0; k < count && k < contacts.size(); ++k) {
    Contact& c = out.contacts[contacts[k]];
    c.fn *= 3 + 0.1 * static_cast<double>(k % 4), c.ft *= 2;
  }
  return out;
}

}  // namespace fnet::testing
