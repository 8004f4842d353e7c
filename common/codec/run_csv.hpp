// A run exported as CSV (fnet-simd --export-csv, or the LAMMPS reference frames):
//   DIR/index.csv                 frame[,step][,time],rho,z   (Z also read: the LAMMPS reference data;
//                                 without step, as from an experiment, a frame's step is its index)
//   DIR/frame_NNNN_particles.csv  id,x,y,r
//   DIR/frame_NNNN_contacts.csv   i,j,fn,ft
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "common/run/run_frame.hpp"

namespace fnet {

// Reads every frame listed in index.csv. Frames are not validated here; a file that cannot be
// parsed throws CsvError naming it.
std::vector<RunFrame> read_csv_run(const std::filesystem::path& dir, const std::string& run_id);

}  // namespace fnet
