// The reference frames from an independent simulator (LAMMPS) under tests/data.
#pragma once

#include <cstddef>

#include "common/topology/frame.hpp"

namespace fnet::testing {

// Frames of tests/data/lammps-mu0.5-seed777, 0-based, read with their particle tables.
std::size_t lammps_frame_count();
Frame lammps_frame(std::size_t index);

}  // namespace fnet::testing
