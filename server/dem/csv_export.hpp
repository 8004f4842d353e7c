// CSV export in the format `fnet-analyze diagram` reads (common/frame_csv.hpp):
//   DIR/index.csv                       frame,step,time,rho,z   (time in τ_c since the compression began)
//   DIR/frame_NNNN_particles.csv        id,x,y,r
//   DIR/frame_NNNN_contacts.csv         i,j,fn,ft     grain–grain, signed F_n, |F_t|
//   DIR/frame_NNNN_wall_contacts.csv    grain,wall,side,fn,ft   (side 0 bottom, 1 right, 2 top, 3 left)
// Numbers are written in the shortest form that reads back to the same double.
#pragma once

#include <filesystem>

#include "server/dem/snapshot.hpp"

namespace fnet::sim {

// Creates DIR and an index.csv holding only the rows of frames < keep_frames (0 for a new run;
// a resumed run keeps the frames its checkpoint had already emitted).
void prepare_csv_dir(const std::filesystem::path& dir, std::size_t keep_frames);

// Writes the frame's files and appends its row to index.csv.
void write_frame_csv(const std::filesystem::path& dir, const FrameSnapshot& frame);

}  // namespace fnet::sim
