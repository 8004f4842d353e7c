// The elastic frictionless gas of the energy-conservation test, shared with the integrator
// benchmark: 400 grains at ρ ≈ 0.35, e_n = 1, μ = 0, random velocities of up to 0.3 d/τ_c.
#pragma once

#include <algorithm>
#include <cmath>

#include "server/dem/diagnostics.hpp"
#include "server/dem/time_step.hpp"

namespace fnet::sim::scenes {

inline Params elastic_gas(Integrator integrator = Integrator::gear, double dt_divisor = 50) {
  Params p;
  p.particles = 400;
  p.box = 30;
  p.en = 1;
  p.mu = 0;
  p.initial_speed = 0.3;
  p.seed = 11;
  p.integrator = integrator;
  p.dt_divisor = dt_divisor;
  return p;
}

// Steps s and returns the worst |E - E0| / E0 (kinetic + elastic), sampled every 10 steps.
inline double worst_energy_drift(Simulation& s, int steps) {
  const double e0 = kinetic_energy(s) + elastic_energy(s);
  double worst = 0;
  for (int k = 0; k < steps; ++k) {
    step(s);
    if (k % 10 == 0) worst = std::max(worst, std::abs(kinetic_energy(s) + elastic_energy(s) - e0) / e0);
  }
  return worst;
}

}  // namespace fnet::sim::scenes
