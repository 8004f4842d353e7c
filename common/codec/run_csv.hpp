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

// The frames index.csv lists, in its order, each header labelled with run_id. A file that cannot
// be parsed throws CsvError naming it, and the line.
std::vector<FrameHeader> read_csv_index(const std::filesystem::path& dir, const std::string& run_id);

// The frame `header` lists: its contacts and particles files read, labelled with its run and index.
// Not validated here; a file that cannot be read throws CsvError naming it.
RunFrame read_csv_frame(const std::filesystem::path& dir, const FrameHeader& header);

// Every frame listed in index.csv: read_csv_index, then read_csv_frame for each.
std::vector<RunFrame> read_csv_run(const std::filesystem::path& dir, const std::string& run_id);

}  // namespace fnet
