// Newton's first law per grain, as a check that a dump's force columns were read as meant: in a
// relaxed packing every grain's contact forces (grains and walls) add up to nearly nothing, while
// a column read as the wrong quantity leaves most grains far out of balance. In 3D as in 2D: the
// force vectors are the frame's own (z 0 in 2D).
#pragma once

#include <cstdint>
#include <vector>

#include "server/sources/lammps_frame.hpp"

namespace fnet::sources {

struct GrainImbalance {
  std::uint32_t grain = 0;
  double net = 0;  // |Σ contact forces on the grain| / the frame's mean contact force
};

struct ForceBalance {
  double mean_force = 0;                   // mean |F| over the contacts, walls included
  std::vector<GrainImbalance> unbalanced;  // net > tolerance, worst first
};

// Throws std::invalid_argument for a frame whose force vectors are unknown (magnitudes only).
ForceBalance force_balance(const LammpsFrame& frame, double tolerance);

}  // namespace fnet::sources
