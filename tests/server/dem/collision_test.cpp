// Binary head-on collisions against the analytic linear spring–dashpot: with ω² = k_n/m̄ − γ_n²/4
// the contact lasts π/ω and the restitution is exp(−γ_n π / (2ω)); for two mean grains (m̄ = 1/2)
// these are τ_c and e_n exactly.
//
// With a fixed step the contact starts and ends at some phase within a step, and the dashpot
// force jumps there (on at −γ m̄ v_n, off while tensile): the velocity change of one partial step
// is uncertain by up to γ_n Δt = −2 ln(e_n) / 50 = 2.8 % of the velocity, with Gear as with
// velocity Verlet or LAMMPS. So a single collision's restitution depends on its phase; averaged
// over phases (what a packing samples) it is within 1 % of the analytic value at Δt = τ_c/50,
// and every phase stays within γ_n Δt. Durations, interpolated between steps, are within 1 %
// for every phase. Each test sweeps the phase of the contact's start over a step.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "server/dem/initial_packing.hpp"
#include "server/dem/time_step.hpp"

namespace fnet::sim {
namespace {

struct Analytic {
  double restitution = 0, duration = 0;
};

Analytic analytic(const Constants& c, double m_bar) {
  const double omega = std::sqrt(c.kn / m_bar - 0.25 * c.gamma_n * c.gamma_n);
  const double t = std::numbers::pi / omega;
  return {std::exp(-0.5 * c.gamma_n * t), t};
}

double overlap(const Simulation& s, std::size_t a, std::size_t b) {
  const double dx = s.x[0][a] - s.x[0][b], dy = s.y[0][a] - s.y[0][b];
  return s.radius[a] + s.radius[b] - std::sqrt(dx * dx + dy * dy);
}

struct Range {
  double lo = 1e9, hi = -1e9, sum = 0;
  int count = 0;
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    sum += v;
    ++count;
  }
  double mean() const { return sum / count; }
};

struct Sweep {
  Range restitution, duration;  // measured / analytic
};

// Body a (a grain) moves along `axis` (0: x, 1: y) into body b. make(phase) builds the run with
// the start shifted by phase (in [0, 1) of a step's approach). The contact's start and end are
// the zero crossings of the overlap, interpolated linearly between steps.
template <class Make>
Sweep sweep(Make make, std::size_t a, std::size_t b, int axis, double approach_speed, const Analytic& want) {
  Sweep out;
  const int phases = 24;
  for (int k = 0; k < phases; ++k) {
    Simulation s = make(static_cast<double>(k) / phases);
    const double dt = s.c.dt;
    double prev = overlap(s, a, b), t_start = -1, t_end = -1;
    for (int n = 0; n < 100000 && t_end < 0; ++n) {
      step(s);
      const double now = overlap(s, a, b), t = static_cast<double>(s.step) * dt;
      if (prev <= 0 && now > 0) t_start = t - dt * now / (now - prev);
      if (prev > 0 && now <= 0 && t_start >= 0) t_end = t - dt * now / (now - prev);
      prev = now;
    }
    EXPECT_GE(t_end, 0) << "no complete collision";
    for (int n = 0; n < 5; ++n) step(s);
    const auto& v = axis == 0 ? s.x[1] : s.y[1];
    const double separation = std::abs(v[a] - v[b]) / dt;
    out.restitution.add(separation / approach_speed / want.restitution);
    out.duration.add((t_end - t_start) / want.duration);
  }
  return out;
}

void check(const Sweep& m, const Constants& c, const char* what) {
  std::printf("%s: e/e_exact mean %.5f range [%.4f, %.4f]; duration/exact mean %.5f range [%.4f, %.4f]\n", what,
              m.restitution.mean(), m.restitution.lo, m.restitution.hi, m.duration.mean(), m.duration.lo,
              m.duration.hi);
  const double phase_bound = 1.05 * c.gamma_n * c.dt;
  EXPECT_NEAR(m.restitution.mean(), 1.0, 0.01) << what;
  EXPECT_LT(std::max(m.restitution.hi - 1, 1 - m.restitution.lo), phase_bound) << what;
  EXPECT_NEAR(m.duration.lo, 1.0, 0.01) << what;
  EXPECT_NEAR(m.duration.hi, 1.0, 0.01) << what;
}

Params collision_params(double polydispersity) {
  Params p;
  p.polydispersity = polydispersity;
  p.box = 20;
  p.mu = 0.5;
  return p;
}

TEST(Collision, MeanGrainsHeadOnGiveTauCAndEn) {
  const Params p = collision_params(0);  // d = 1 exactly: mass 1, m̄ = 1/2
  const Constants c = derive(p);
  const Analytic want = analytic(c, 0.5);
  EXPECT_NEAR(want.duration, c.tau_c, 1e-12);
  EXPECT_NEAR(want.restitution, p.en, 1e-12);
  for (double speed : {0.01, 0.3, 1.0}) {  // each grain, d / τ_c
    const double v = speed / c.tau_c;
    const Sweep m = sweep(
        [&](double phase) {
          const double gap = 0.2 + 2 * v * c.dt * phase;
          const std::vector<GrainInit> g = {{10 - 0.5 - gap / 2, 10, 0.5, v, 0, 0},
                                            {10 + 0.5 + gap / 2, 10, 0.5, -v, 0, 0}};
          return make_custom(p, g);
        },
        0, 1, 0, 2 * v, want);
    check(m, c, ("mean grains, speed " + std::to_string(speed)).c_str());
  }
}

TEST(Collision, UnequalGrainsUseTheReducedMass) {
  const Params p = collision_params(0.4);  // masses d² / <d²>
  const Constants c = derive(p);
  for (double r1 : {0.4, 0.45}) {
    const double r2 = 1 - r1;
    const double m1 = 4 * r1 * r1 / c.mean_d2, m2 = 4 * r2 * r2 / c.mean_d2;
    const Analytic want = analytic(c, m1 * m2 / (m1 + m2));
    const double v = 0.2 / c.tau_c;
    const Sweep m = sweep(
        [&](double phase) {
          const double gap = 0.2 + 2 * v * c.dt * phase;
          const std::vector<GrainInit> g = {{10 - r1 - gap / 2, 10, r1, v, 0, 0},
                                            {10 + r2 + gap / 2, 10, r2, -v, 0, 0}};
          return make_custom(p, g);
        },
        0, 1, 0, 2 * v, want);
    check(m, c, ("grains d " + std::to_string(2 * r1) + " and " + std::to_string(2 * r2)).c_str());
  }
}

TEST(Collision, GrainOnWallParticleSeesAnInfinitelyHeavyWall) {
  const Params p = collision_params(0);
  const Constants c = derive(p);
  const Analytic want = analytic(c, 1.0);  // m̄ = m_grain = 1
  const double v = 0.2 / c.tau_c;
  // Bottom wall particle 10 sits at (9.5, -0.5): drop a grain on it head-on.
  const std::size_t wall = 1 + 10;
  const Sweep m = sweep(
      [&](double phase) {
        const std::vector<GrainInit> g = {{9.5, 0.8 + v * c.dt * phase, 0.5, 0, -v, 0}};
        Simulation s = make_custom(p, g);
        EXPECT_NEAR(s.x[0][wall], 9.5, 1e-12);
        EXPECT_NEAR(s.y[0][wall], -0.5, 1e-12);
        return s;
      },
      0, wall, 1, v, want);
  check(m, c, "grain on a wall particle");
}

}  // namespace
}  // namespace fnet::sim
