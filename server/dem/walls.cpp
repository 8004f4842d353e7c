#include "server/dem/walls.hpp"

#include <cmath>

#include "server/dem/run_state.hpp"

namespace fnet::sim {

void add_walls(Simulation& s) {
  const double dw = s.params.wall_diameter, box = s.params.box.value();
  const double ring = box + dw;  // side of the square through the wall particles' centres
  const auto per_side = static_cast<std::size_t>(std::ceil(ring / dw - 1e-9));
  const double spacing = ring / static_cast<double>(per_side);  // <= dw: no gap a grain passes
  const double lo = -0.5 * dw, hi = box + 0.5 * dw;
  for (int side = 0; side < 4; ++side) {
    for (std::size_t k = 0; k < per_side; ++k) {
      const double t = static_cast<double>(k) * spacing;
      double x = 0, y = 0, dx = 0, dy = 0;
      switch (side) {
        case 0:
          x = lo + t, y = lo, dy = 1;
          break;  // bottom, moves up
        case 1:
          x = hi, y = lo + t, dx = -1;
          break;  // right, moves left
        case 2:
          x = hi - t, y = hi, dy = -1;
          break;  // top, moves down
        default:
          x = lo, y = hi - t, dx = 1;
          break;  // left, moves right
      }
      s.wall_x0.push_back(x);
      s.wall_y0.push_back(y);
      s.wall_dir_x.push_back(dx);
      s.wall_dir_y.push_back(dy);
      s.wall_side.push_back(side);
      s.radius.push_back(0.5 * dw);
      s.inv_mass.push_back(0.0);  // infinitely heavy: m̄ = m_grain
    }
  }
  s.nw = s.wall_x0.size();
}

double wall_offset(const Simulation& s) { return static_cast<double>(s.compress_step) * s.c.dt * s.c.wall_speed; }

double interior_side(const Simulation& s) { return s.params.box.value() - 2 * wall_offset(s); }

double packing_fraction(const Simulation& s) {
  const double side = interior_side(s);
  return s.grain_area / (side * side);
}

void place_walls(Simulation& s) {
  const double offset = wall_offset(s);
  const double v = s.walls_moving ? s.c.wall_speed * s.c.dt : 0.0;
  for (std::size_t k = 0; k < s.nw; ++k) {
    const std::size_t b = s.n + k;
    s.x[0][b] = s.wall_x0[k] + s.wall_dir_x[k] * offset;
    s.y[0][b] = s.wall_y0[k] + s.wall_dir_y[k] * offset;
    s.x[1][b] = s.wall_dir_x[k] * v;
    s.y[1][b] = s.wall_dir_y[k] * v;
    s.th[1][b] = 0;
  }
}

}  // namespace fnet::sim
