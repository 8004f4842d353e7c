#include "server/dem/diagnostics.hpp"

#include <cmath>
#include <cstdint>

namespace fnet::sim {

double translational_energy(const Simulation& s) {
  const double inv_dt2 = 1 / (s.c.dt * s.c.dt);
  double e = 0;
  for (std::size_t i = 0; i < s.n; ++i) e += 0.5 * (s.x[1][i] * s.x[1][i] + s.y[1][i] * s.y[1][i]) / s.inv_mass[i];
  return e * inv_dt2;
}

double kinetic_energy(const Simulation& s) {
  const double inv_dt2 = 1 / (s.c.dt * s.c.dt);
  double e = 0;
  for (std::size_t i = 0; i < s.n; ++i) {
    const double v2 = s.x[1][i] * s.x[1][i] + s.y[1][i] * s.y[1][i];
    e += 0.5 * (v2 / s.inv_mass[i] + s.th[1][i] * s.th[1][i] / s.inv_inertia[i]) * inv_dt2;
  }
  return e;
}

double elastic_energy(const Simulation& s) {
  double e = 0;
  const NeighbourList& l = s.list;
  for (std::size_t i = 0; i < s.n; ++i) {
    for (std::uint32_t p = l.offset[i]; p < l.offset[i + 1]; ++p) {
      const std::uint32_t j = l.partner[p];
      const double dx = s.x[0][i] - s.x[0][j], dy = s.y[0][i] - s.y[0][j];
      const double overlap = s.radius[i] + s.radius[j] - std::sqrt(dx * dx + dy * dy);
      if (overlap > 0) e += 0.5 * s.c.kn * overlap * overlap;
    }
  }
  return e;
}

double coordination(const Simulation& s) {
  std::size_t contacts = 0;
  const NeighbourList& l = s.list;
  for (std::size_t p = 0; p < l.partner.size(); ++p) contacts += (l.partner[p] < s.n && l.touching[p] && l.fn[p] > 0);
  return s.n == 0 ? 0.0 : 2.0 * static_cast<double>(contacts) / static_cast<double>(s.n);
}

}  // namespace fnet::sim
