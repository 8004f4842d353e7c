// The state of one DEM run: grains and wall particles as structure-of-arrays, the Verlet list
// with the contact history, and the protocol's clock. A value type: copy it to fork a run.
//
// Bodies 0..n-1 are grains; n..n+nw-1 are wall particles, whose motion is prescribed (the walls
// move inward at v_c during the compression) and which count as infinitely heavy (m̄ = m_grain
// for a grain–wall contact).
//
// Kinematic arrays hold Gear's scaled derivatives: x[k] = (d^k x / dt^k) Δt^k / k!, so x[1] is
// the velocity times Δt. Velocity Verlet uses x[0], x[1] with the same scaling.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "server/dem/neighbour_list.hpp"
#include "server/dem/params.hpp"

namespace fnet::sim {

inline constexpr int kGearOrder = 5;  // values x, x', x'', x''', x'''' (Taylor predictor through the 4th derivative)

enum class Phase : std::int32_t { relax = 0, compress = 1, done = 2 };

struct Simulation {
  Params params;
  Constants c;
  std::size_t n = 0;   // grains
  std::size_t nw = 0;  // wall particles

  // Per body (grains then walls).
  std::vector<double> radius, inv_mass;
  std::array<std::vector<double>, kGearOrder> x, y, th;  // levels 0, 1: n + nw; levels >= 2: n
  std::vector<double> fx, fy, torque;                    // forces of the last evaluation
  std::vector<double> inv_inertia;                       // grains only

  // Wall particles: position at the start of the compression and inward direction (unit axis).
  std::vector<double> wall_x0, wall_y0, wall_dir_x, wall_dir_y;
  std::vector<std::int32_t> wall_side;  // 0 bottom, 1 right, 2 top, 3 left

  NeighbourList list;

  // Protocol clock.
  Phase phase = Phase::relax;
  std::int64_t step = 0;            // all steps taken
  std::int64_t compress_step = 0;   // steps since the compression started (walls at offset v·Δt·compress_step)
  std::int64_t compress_steps = 0;  // length of the compression (steps to reach rho_final)
  std::size_t next_frame = 0;
  bool walls_moving = false;

  double grain_area = 0;  // Σ π r²
};

}  // namespace fnet::sim
