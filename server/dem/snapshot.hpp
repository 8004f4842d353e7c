// A frame of a run as fnet-simd's sinks receive it: the CSV export reads it directly; DDS and the
// HDF5 run file take the RunFrame that run_frame() (output_sinks.hpp) makes of it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/topology/frame.hpp"

namespace fnet::sim {

struct Simulation;

// A grain touching a wall particle. side: 0 bottom, 1 right, 2 top, 3 left.
struct WallContact {
  std::int64_t grain = 0;
  std::int64_t wall_particle = 0;  // 0-based among the wall particles
  std::int32_t side = 0;
  double fn = 0, ft = 0;
};

struct FrameSnapshot {
  std::string run_id;
  std::size_t index = 0;  // frame number within the compression, 0-based
  std::int64_t step = 0;  // steps since the compression started
  double time = 0;        // since the compression started, in τ_c
  double rho = 0;         // Σ π r² / area of the free interior
  double z = 0;           // 2 × grain–grain contacts with F_n > 0 / N
  fnet::Frame frame;      // grains (x, y, r) and grain–grain contacts (i < j, signed F_n, |F_t|)
  std::vector<WallContact> wall_contacts;
};

// Where frames go. A plain callable: several sinks are composed by calling them in turn.
using FrameSink = std::function<void(const FrameSnapshot&)>;

// The current state as a frame. Positions are those at the end of the step; forces (and so the
// contact set: pairs with overlap > 0) those evaluated during it.
FrameSnapshot snapshot(const Simulation& s, const std::string& run_id, std::size_t index);

}  // namespace fnet::sim
