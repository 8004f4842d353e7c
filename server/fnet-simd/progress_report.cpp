#include "server/fnet-simd/progress_report.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace fnet::sim {
namespace {

std::string duration(double seconds) {
  if (seconds < 0 || !std::isfinite(seconds)) return "?";
  const auto s = static_cast<long long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%lldh%02lldm", s / 3600, s / 60 % 60);
  else
    std::snprintf(buf, sizeof buf, "%lldm%02llds", s / 60, s % 60);
  return buf;
}

}  // namespace

void print_progress(const Progress& p) {
  if (p.phase == Phase::relax) {
    std::fprintf(stderr,
                 "fnet-simd: relaxing  step %lld  translational KE/grain %.3g (target %.3g)  rho %.4f  Z %.3f  %.0f "
                 "steps/s\n",
                 static_cast<long long>(p.step), p.kinetic_energy, p.relax_target, p.rho, p.z, p.steps_per_second);
  } else {
    std::fprintf(stderr, "fnet-simd: %s  rho %.4f  Z %.3f  frames %zu/%zu  step %lld/%lld  %.0f steps/s  ETA %s\n",
                 p.phase == Phase::done ? "done" : "compressing", p.rho, p.z, p.frames_done, p.frames,
                 static_cast<long long>(p.compress_step), static_cast<long long>(p.compress_steps), p.steps_per_second,
                 duration(p.eta_seconds).c_str());
  }
}

void print_relaxation(const Relaxation& r) {
  if (r.capped)
    std::fprintf(stderr,
                 "fnet-simd: warning: relaxation stopped by --relax-max-time after %lld steps, translational "
                 "kinetic energy per grain %.3g above the target %.3g: compressing a start that is not at rest\n",
                 static_cast<long long>(r.steps), r.energy, r.target);
  else
    std::fprintf(stderr, "fnet-simd: relaxed in %lld steps: translational kinetic energy per grain %.3g < %.3g\n",
                 static_cast<long long>(r.steps), r.energy, r.target);
}

}  // namespace fnet::sim
