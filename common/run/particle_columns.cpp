#include "common/run/particle_columns.hpp"

namespace fnet {

ParticleColumns particle_columns(const Frame& frame, bool z_of_2d) {
  ParticleColumns out;
  out.xyr.reserve(3 * frame.particles.size());
  for (const Particle& p : frame.particles) out.xyr.insert(out.xyr.end(), {p.x, p.y, p.r});
  if (frame.dimension == 3 || z_of_2d) {
    out.z.reserve(frame.particles.size());
    for (const Particle& p : frame.particles) out.z.push_back(p.z);
  }
  return out;
}

std::string set_particles(Frame& frame, const double* xyr, std::size_t xyr_values, const double* z,
                          std::size_t z_values) {
  if (xyr_values % 3 != 0) return "particle array length " + std::to_string(xyr_values) + " is not a multiple of 3";
  const std::size_t n = xyr_values / 3;
  if (z_values != 0 && z_values != n)
    return std::to_string(z_values) + " z values for " + std::to_string(n) + " particles";
  frame.particles.resize(n);
  for (std::size_t k = 0; k < n; ++k)
    frame.particles[k] = {xyr[3 * k], xyr[3 * k + 1], xyr[3 * k + 2], z_values ? z[k] : 0.0};
  return {};
}

}  // namespace fnet
