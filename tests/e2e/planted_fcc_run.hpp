// A 3D run for the service tests: three frames of a jittered FCC packing (tests/support), the
// middle one with a change planted in one cell of a k x k x k grid, written as a run file
// (fnet-run-3) that fnet-analyze publish reads.
#pragma once

#include <filesystem>
#include <string>

#include "common/topology/frame.hpp"

namespace fnet::e2e {

struct PlantedCell {
  int cells = 5;  // FCC unit cells per side: 4·cells³ spheres
  int k = 3;      // the grid, and the cell (layer, row, col) of it whose contacts change
  int layer = 2, row = 0, col = 1;
};

// Frames 0 and 2 the packing, frame 1 the packing with the forces of 20 contacts of the cell
// changed (each at least 0.2 inside its faces).
struct Planted3D {
  Frame original, planted;
};

Planted3D plant_in_cell(const PlantedCell& where);

// The run file of run `run_id`: frames 0, 1, 2 (original, planted, original), rho 0.74, Z 12.
std::filesystem::path write_run_file_3d(const std::filesystem::path& path, const std::string& run_id,
                                        const Planted3D& run);

}  // namespace fnet::e2e
