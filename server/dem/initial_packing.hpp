// The starts of a run: the paper's lattice (grains, walls, the first forces) or grains placed by
// hand for tests.
#pragma once

#include <span>

#include "server/dem/params.hpp"
#include "server/dem/run_state.hpp"

namespace fnet::sim {

// One grain to place by hand (tests): position, radius, velocity (d / internal time), spin.
struct GrainInit {
  double x = 0, y = 0, r = 0.5, vx = 0, vy = 0, w = 0;
};

// The paper's start: grains on a square lattice filling the box, random diameters and velocities
// drawn from the seed, walls at rest. Deterministic for a given Params. Without p.box the box is
// sized so that the grains drawn fill p.rho_initial of it; the returned params hold the box used.
// Throws std::invalid_argument when the lattice would be denser than d_ave or rho_final is not
// above the start's packing fraction.
Simulation make_lattice(const Params& p);

// Grains placed by hand inside the walls of a box of side p.box, which must be set (tests).
Simulation make_custom(const Params& p, std::span<const GrainInit> grains);

}  // namespace fnet::sim
