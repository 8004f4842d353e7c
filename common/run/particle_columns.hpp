// A frame's particles as the flat columns the transport and the stores carry: x, y, r per particle,
// and z per particle (0 in a 2D frame).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "common/topology/frame.hpp"

namespace fnet {

struct ParticleColumns {
  std::vector<double> xyr;  // x, y, r per particle
  std::vector<double> z;    // z per particle; empty for a 2D frame when z_of_2d is false
};

// z_of_2d: whether a 2D frame's z (every one 0) is wanted too, as the stores keep it.
ParticleColumns particle_columns(const Frame& frame, bool z_of_2d);

// Fills frame.particles from `xyr` (3 values per particle) and `z`: one value per particle, or
// none (every z is 0). Returns what is wrong, or an empty string when nothing is.
std::string set_particles(Frame& frame, const double* xyr, std::size_t xyr_values, const double* z,
                          std::size_t z_values);

}  // namespace fnet
