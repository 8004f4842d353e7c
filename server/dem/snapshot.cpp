#include "server/dem/snapshot.hpp"

#include <cmath>

#include "server/dem/diagnostics.hpp"
#include "server/dem/walls.hpp"

namespace fnet::sim {

FrameSnapshot snapshot(const Simulation& s, const std::string& run_id, std::size_t index) {
  FrameSnapshot f;
  f.run_id = run_id;
  f.index = index;
  f.step = s.compress_step;
  f.time = static_cast<double>(s.compress_step) / s.params.dt_divisor;
  f.rho = packing_fraction(s);
  f.z = coordination(s);
  f.frame.label = run_id + " frame " + std::to_string(index);
  f.frame.particle_count = s.n;
  f.frame.particles.resize(s.n);
  for (std::size_t i = 0; i < s.n; ++i) f.frame.particles[i] = {s.x[0][i], s.y[0][i], s.radius[i]};
  const NeighbourList& l = s.list;
  for (std::size_t i = 0; i < s.n; ++i) {
    for (std::uint32_t p = l.offset[i]; p < l.offset[i + 1]; ++p) {
      if (!l.touching[p]) continue;
      const std::uint32_t j = l.partner[p];
      if (j < s.n) {
        f.frame.contacts.push_back(
            {static_cast<std::int64_t>(i), static_cast<std::int64_t>(j), l.fn[p], std::sqrt(l.ft2[p])});
      } else {
        const std::size_t k = j - s.n;
        f.wall_contacts.push_back(
            {static_cast<std::int64_t>(i), static_cast<std::int64_t>(k), s.wall_side[k], l.fn[p], std::sqrt(l.ft2[p])});
      }
    }
  }
  return f;
}

}  // namespace fnet::sim
