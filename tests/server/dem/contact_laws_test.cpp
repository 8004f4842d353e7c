// Properties that must hold at every contact of every step, and the conservation laws.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "server/dem/diagnostics.hpp"
#include "server/dem/initial_packing.hpp"
#include "server/dem/protocol.hpp"
#include "server/dem/time_step.hpp"
#include "tests/server/dem/elastic_gas.hpp"

namespace fnet::sim {
namespace {

// A small compression that reaches jamming quickly: 300 grains, walls at 0.01 d/τ_c.
Params small_compression(double mu) {
  Params p;
  p.particles = 300;
  p.box = std::sqrt(300 * 0.25 * 3.141592653589793 * (1 + 0.4 * 0.4 / 12) / 0.64);
  p.mu = mu;
  p.compression_speed = 1e-2;
  p.relax_energy = 1e-4;
  p.rho_final = 0.86;
  p.frames = 5;
  p.seed = 3;
  return p;
}

// Coulomb (A5) and Newton's third law at every step of a relaxation and compression through
// jamming. Newton: the forces on all bodies, wall particles included, sum to zero.
TEST(ContactLaws, CoulombAndNewtonAtEveryContactOfEveryStep) {
  Simulation s = make_lattice(small_compression(0.5));
  std::size_t checked = 0, sliding = 0;
  double worst_newton = 0;
  RunOptions o;
  o.max_steps = 1;
  while (!run(s, o)) {
    const NeighbourList& l = s.list;
    for (std::size_t p = 0; p < l.partner.size(); ++p) {
      if (!l.touching[p]) continue;
      ++checked;
      const double cap = s.params.mu * std::abs(l.fn[p]);
      const double ft = std::sqrt(l.ft2[p]);
      ASSERT_LE(ft, cap * (1 + 1e-12) + 1e-300) << "step " << s.step << " pair " << p;
      sliding += ft >= cap * (1 - 1e-12) && cap > 0;
    }
    double sx = 0, sy = 0, scale = 0;
    for (std::size_t b = 0; b < s.fx.size(); ++b) {
      sx += s.fx[b];
      sy += s.fy[b];
      scale += std::abs(s.fx[b]) + std::abs(s.fy[b]);
    }
    if (scale > 0) worst_newton = std::max(worst_newton, (std::abs(sx) + std::abs(sy)) / scale);
  }
  std::printf("%zu contact-steps checked, %zu at the Coulomb cap; worst |sum F| / sum |F| = %.3g\n", checked, sliding,
              worst_newton);
  EXPECT_GT(checked, 100000u);
  EXPECT_GT(sliding, 1000u);  // the cap was exercised
  EXPECT_LT(worst_newton, 1e-12);
}

// Total linear momentum of a wall-free granular gas is conserved (every contact force has its
// opposite) and the tangential spring stays in the tangent plane (A3).
TEST(ContactLaws, MomentumConservedAndSpringTangent) {
  Params p;
  p.particles = 200;
  p.box = 30;
  p.initial_speed = 0.05;
  p.mu = 0.5;
  Simulation s = make_lattice(p);
  // Keep grains away from the walls: shrink the lattice towards the centre.
  for (std::size_t i = 0; i < s.n; ++i) {
    s.x[0][i] = 15 + 0.7 * (s.x[0][i] - 15);
    s.y[0][i] = 15 + 0.7 * (s.y[0][i] - 15);
  }
  const auto momentum = [&] {
    double px = 0, py = 0;
    for (std::size_t i = 0; i < s.n; ++i) {
      px += s.x[1][i] / s.inv_mass[i];
      py += s.y[1][i] / s.inv_mass[i];
    }
    return std::pair{px / s.c.dt, py / s.c.dt};
  };
  const auto [px0, py0] = momentum();
  double worst_tangent = 0;
  std::size_t contacts = 0;
  for (int k = 0; k < 3000; ++k) {
    step(s);
    for (std::size_t i = 0; i < s.n; ++i) {
      for (std::uint32_t q = s.list.offset[i]; q < s.list.offset[i + 1]; ++q) {
        if (!s.list.touching[q]) continue;
        ++contacts;
        const std::uint32_t j = s.list.partner[q];
        ASSERT_LT(j, s.n) << "a grain reached a wall";
        const double dx = s.x[0][i] - s.x[0][j], dy = s.y[0][i] - s.y[0][j], r = std::hypot(dx, dy);
        const double h = std::hypot(s.list.hx[q], s.list.hy[q]);
        // ξ was projected with the predicted n; the corrected one differs by O(Δt² a).
        if (h > 0) worst_tangent = std::max(worst_tangent, std::abs(s.list.hx[q] * dx + s.list.hy[q] * dy) / (r * h));
      }
    }
  }
  const auto [px1, py1] = momentum();
  std::printf("momentum drift (%.3g, %.3g) of |p| scale %.3g; %zu contacts; worst |n.xi|/|xi| %.3g\n", px1 - px0,
              py1 - py0, std::hypot(px0, py0) + static_cast<double>(s.n) * p.initial_speed / s.c.tau_c, contacts,
              worst_tangent);
  EXPECT_GT(contacts, 1000u);
  EXPECT_NEAR(px1, px0, 1e-9);
  EXPECT_NEAR(py1, py0, 1e-9);
  EXPECT_LT(worst_tangent, 1e-2);
}

// Elastic (e_n = 1) frictionless gas: kinetic + elastic energy is conserved up to a bounded drift.
TEST(ContactLaws, ElasticFrictionlessGasConservesEnergy) {
  const Params p = scenes::elastic_gas();
  Simulation s = make_lattice(p);
  const double e0 = kinetic_energy(s) + elastic_energy(s);
  const int steps = 50000;
  const double worst = scenes::worst_energy_drift(s, steps);
  const double end = (kinetic_energy(s) + elastic_energy(s) - e0) / e0;
  std::printf("elastic gas, %d steps (%.0f tau_c): relative energy drift at end %.3g, worst %.3g\n", steps,
              steps / p.dt_divisor, end, worst);
  EXPECT_LT(worst, 2e-3);
}

// A jammed packing, relaxed with the walls at rest: every grain is in force balance.
TEST(ContactLaws, RelaxedJammedPackingIsInForceBalance) {
  Simulation s = make_lattice(small_compression(0.5));
  RunOptions o;
  ASSERT_TRUE(run(s, o));
  ASSERT_GT(coordination(s), 3.0);
  for (int k = 0; k < 100000; ++k) step(s);  // walls stopped at the end of the protocol
  double mean_fn = 0;
  std::size_t contacts = 0;
  for (std::size_t q = 0; q < s.list.partner.size(); ++q)
    if (s.list.touching[q]) mean_fn += std::abs(s.list.fn[q]), ++contacts;
  mean_fn /= static_cast<double>(contacts);
  double worst_force = 0, worst_torque = 0;
  for (std::size_t i = 0; i < s.n; ++i) {
    worst_force = std::max(worst_force, std::hypot(s.fx[i], s.fy[i]));
    worst_torque = std::max(worst_torque, std::abs(s.torque[i]) / s.radius[i]);
  }
  std::printf(
      "relaxed packing Z = %.3f, mean |F_n| = %.4g: worst |sum F| / mean = %.3g, worst |torque|/r / mean = "
      "%.3g, KE/grain %.3g\n",
      coordination(s), mean_fn, worst_force / mean_fn, worst_torque / mean_fn,
      kinetic_energy(s) / static_cast<double>(s.n));
  EXPECT_LT(worst_force / mean_fn, 1e-4);
  EXPECT_LT(worst_torque / mean_fn, 1e-4);
}

}  // namespace
}  // namespace fnet::sim
