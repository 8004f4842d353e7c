// Energies and the coordination number of a run's current state.
#pragma once

#include "server/dem/run_state.hpp"

namespace fnet::sim {

// Diagnostics, in internal units.
double kinetic_energy(const Simulation& s);        // translational + rotational, grains
double translational_energy(const Simulation& s);  // Σ m v² / 2, grains
double elastic_energy(const Simulation& s);        // Σ k_n x² / 2 over touching pairs
double coordination(const Simulation& s);          // Z = 2 × grain–grain contacts with F_n > 0 / n

}  // namespace fnet::sim
