// What advances a run by one time step; the state it advances is run_state.hpp.
#pragma once

#include "server/dem/run_state.hpp"

namespace fnet::sim {

class Workers;

// One time step with the configured integrator: predict, walls, list update, forces, correct.
// With a team of threads (workers.hpp) the Gear step and the forces run split over it, giving
// the same bits as without.
void step(Simulation& s, Workers* workers = nullptr);

// Multiplies every grain's velocity by `factor` (the relaxation's damping; spins are left alone).
void damp_velocities(Simulation& s, double factor);

}  // namespace fnet::sim
