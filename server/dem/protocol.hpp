// The paper's protocol: relax with the walls at rest until the grains are quiescent, then move
// the walls inward at v_c until ρ reaches params.rho_final. The relaxation only has to reach an
// unjammed start at rest (the results do not depend on the initial velocities), so it ends when
// the translational kinetic energy per grain falls below params.relax_energy (tested every
// kRelaxCheck steps; free rattlers may spin forever, their spin carries no force), and grain
// velocities decay at params.relax_damping meanwhile. The compression has no such damping. Frames are taken at fixed
// time intervals over the compression: frame k of K at compression step ⌊k S / (K − 1)⌋, S the compression's length, so
// frame 0 is the relaxed packing and frame K − 1 the final one.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "server/dem/run_state.hpp"
#include "server/dem/snapshot.hpp"

namespace fnet::sim {

class Workers;

inline constexpr std::int64_t kRelaxCheck = 50;

struct Progress {
  Phase phase = Phase::relax;
  std::int64_t step = 0;           // all steps
  std::int64_t compress_step = 0;  // of compress_steps
  std::int64_t compress_steps = 0;
  std::size_t frames_done = 0, frames = 0;
  double rho = 0, z = 0;
  double kinetic_energy = 0;    // translational, per grain, m d² / τ_c² (the relaxation's criterion)
  double relax_target = 0;      // params.relax_energy
  double steps_per_second = 0;  // since the previous report
  double eta_seconds = -1;      // of the compression; -1 while relaxing
};

// How the relaxation ended.
struct Relaxation {
  std::int64_t steps = 0;
  double energy = 0;    // translational kinetic energy per grain, m d² / τ_c²
  double target = 0;    // params.relax_energy
  bool capped = false;  // ended by params.relax_max_time, not by reaching the target
};

struct RunOptions {
  std::string run_id = "fnet-simd";
  FrameSink sink;                                     // every frame, in order
  std::function<void(const Simulation&)> checkpoint;  // after every frame and every checkpoint_seconds
  double checkpoint_seconds = 60;
  std::function<void(const Progress&)> progress;   // every progress_seconds
  std::function<void(const Relaxation&)> relaxed;  // once, when the compression starts
  double progress_seconds = 2;
  std::int64_t max_steps = -1;        // stop after this many steps of this call (tests), -1: run to the end
  std::function<bool()> should_stop;  // polled every 1024 steps (signals); true stops the run
  Workers* workers = nullptr;         // a team for the steps (same results), or none
};

// Number of compression steps to go from the box side to ρ = rho_final, and a frame's step.
std::int64_t compression_length(const Simulation& s);
std::int64_t frame_step(const Simulation& s, std::size_t frame);

// Runs from wherever s is (fresh, relaxed or resumed from a checkpoint) to the end of the
// protocol or max_steps. Returns true when the last frame has been emitted.
bool run(Simulation& s, const RunOptions& options);

}  // namespace fnet::sim
