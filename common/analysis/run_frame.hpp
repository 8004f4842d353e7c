// A frame as it travels from the simulation to the analysis: the force network plus where it sits
// in its run.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/topology/frame.hpp"

namespace fnet {

struct WallContact {
  std::uint32_t particle = 0;
  double fn = 0, ft = 0;  // signed normal force, tangential magnitude
  bool operator==(const WallContact&) const = default;
};

struct FrameHeader {
  std::string run_id;
  std::uint32_t index = 0;  // 0-based within the run
  std::uint64_t step = 0;
  double time = 0;
  double rho = 0;  // packing fraction
  double z = 0;    // 2 x grain-grain contacts with F_n > 0 / N
  bool operator==(const FrameHeader&) const = default;
};

struct RunFrame {
  FrameHeader header;
  Frame frame;  // frame.label names run and index
  std::vector<WallContact> wall_contacts;
};

// The parameters of a run as the simulation announces them; config_json holds every parameter.
struct RunInfo {
  std::string run_id;
  std::uint32_t particles = 0;
  double polydispersity = 0, friction = 0, k_n = 0, restitution = 0, kt_over_kn = 0;
  double compression_speed = 0, dt = 0, final_density = 0;
  std::uint32_t frames = 0;
  std::uint64_t seed = 0;
  std::string config_json;
  bool operator==(const RunInfo&) const = default;
};

// "run R frame K": how every message about a frame names it.
std::string frame_label(const std::string& run_id, std::uint32_t index);

}  // namespace fnet
