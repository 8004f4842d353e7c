// The state of a run as a LAMMPS data file (atom_style sphere, 2D), so that LAMMPS can run the
// same system from the same start (tests/server/dem/lammps/in.compress reads it).
//   type 1: grains; types 2..5: wall particles of the bottom, right, top, left walls.
//   LAMMPS derives a sphere's mass from its data-file density as 4/3 π r³ ρ even in 2D, so each
//   atom's density is chosen to give exactly fnet's mass (walls: 1e12, effectively infinite).
#pragma once

#include <filesystem>

#include "server/dem/run_state.hpp"

namespace fnet::sim {

void write_lammps_data(const Simulation& s, const std::filesystem::path& path);

}  // namespace fnet::sim
