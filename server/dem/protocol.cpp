#include "server/dem/protocol.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "server/dem/diagnostics.hpp"
#include "server/dem/time_step.hpp"
#include "server/dem/walls.hpp"

namespace fnet::sim {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void start_compression(Simulation& s) {
  s.phase = Phase::compress;
  s.walls_moving = true;
  s.compress_step = 0;
  s.compress_steps = compression_length(s);
  s.next_frame = 0;
}

}  // namespace

std::int64_t compression_length(const Simulation& s) {
  const double side_final = std::sqrt(s.grain_area / s.params.rho_final);
  const double travel = 0.5 * (s.params.box.value() - side_final);
  if (travel <= 0) return 0;
  return static_cast<std::int64_t>(std::ceil(travel / (s.c.wall_speed * s.c.dt)));
}

std::int64_t frame_step(const Simulation& s, std::size_t frame) {
  const auto k = static_cast<std::int64_t>(frame), last = static_cast<std::int64_t>(s.params.frames - 1);
  return k * s.compress_steps / last;
}

bool run(Simulation& s, const RunOptions& o) {
  const Clock::time_point started = Clock::now();
  Clock::time_point last_checkpoint = started, last_progress = started;
  std::int64_t steps_at_last_progress = s.step;
  std::int64_t taken = 0;
  const double tau2 = s.c.tau_c * s.c.tau_c;
  const auto ke_per_grain = [&] { return translational_energy(s) / static_cast<double>(s.n) * tau2; };
  const double damping = std::exp(-s.params.relax_damping / s.params.dt_divisor);  // per step of τ_c / divisor

  const auto emit_due_frames = [&] {
    while (s.phase == Phase::compress && s.next_frame < s.params.frames &&
           s.compress_step == frame_step(s, s.next_frame)) {
      if (o.sink) o.sink(snapshot(s, o.run_id, s.next_frame));
      ++s.next_frame;
      if (s.next_frame == s.params.frames) {
        s.phase = Phase::done;
        s.walls_moving = false;
      }
      if (o.checkpoint) {
        o.checkpoint(s);
        last_checkpoint = Clock::now();
      }
    }
  };

  const auto report = [&](double elapsed) {
    Progress p;
    p.phase = s.phase;
    p.step = s.step;
    p.compress_step = s.compress_step;
    p.compress_steps = s.compress_steps;
    p.frames_done = s.next_frame;
    p.frames = s.params.frames;
    p.rho = packing_fraction(s);
    p.z = coordination(s);
    p.kinetic_energy = ke_per_grain();
    p.relax_target = s.params.relax_energy;
    p.steps_per_second = static_cast<double>(s.step - steps_at_last_progress) / elapsed;
    if (s.phase == Phase::compress && p.steps_per_second > 0)
      p.eta_seconds = static_cast<double>(s.compress_steps - s.compress_step) / p.steps_per_second;
    o.progress(p);
  };

  emit_due_frames();  // frame 0 of a compression that starts right here (resume at a frame)
  while (s.phase != Phase::done) {
    if (o.max_steps >= 0 && taken >= o.max_steps) return false;
    step(s, o.workers);
    ++taken;
    if (s.phase == Phase::relax) {
      if (damping != 1) damp_velocities(s, damping);
      if (s.step % kRelaxCheck == 0) {
        const double energy = ke_per_grain();
        const bool cold = energy < s.params.relax_energy;
        const bool too_long = static_cast<double>(s.step) / s.params.dt_divisor >= s.params.relax_max_time;
        if (cold || too_long) {
          if (o.relaxed) o.relaxed({s.step, energy, s.params.relax_energy, !cold});
          start_compression(s);
        }
      }
    }
    emit_due_frames();
    if ((taken & 1023) == 0) {
      if (o.should_stop && o.should_stop()) return false;
      if (o.progress && seconds_since(last_progress) >= o.progress_seconds) {
        report(seconds_since(last_progress));
        last_progress = Clock::now();
        steps_at_last_progress = s.step;
      }
      if (o.checkpoint && seconds_since(last_checkpoint) >= o.checkpoint_seconds) {
        o.checkpoint(s);
        last_checkpoint = Clock::now();
      }
    }
  }
  if (o.progress) report(std::max(seconds_since(last_progress), 1e-9));
  return true;
}

}  // namespace fnet::sim
