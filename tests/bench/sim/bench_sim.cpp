// fnet-simd engine benchmarks (not run by CTest):
//  1. Gear-4 (5-value) vs velocity Verlet at Δt = τ_c/25, /50, /100: restitution error of binary
//     collisions (0.8–1.2 pair, phase-averaged and worst phase), energy drift of an elastic
//     frictionless gas over 200 τ_c, and cost per step of a 2000-grain packing near jamming.
//  2. Cost against N (1e3 .. 1e5 grains) on the relaxing lattice at ρ = 0.63.
//  3. With --threads (alone): cost per step on 1 and 2 threads, dense packing and relaxing lattice.
// Usage: fnet_sim_bench [max_N] [--cost-only]   (max_N default 100000; --cost-only skips part 1)
//        fnet_sim_bench --threads
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "server/dem/initial_packing.hpp"
#include "server/dem/protocol.hpp"
#include "server/dem/time_step.hpp"
#include "server/dem/workers.hpp"
#include "tests/server/dem/elastic_gas.hpp"

using namespace fnet::sim;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct RestitutionError {
  double mean = 0, worst = 0;
};

RestitutionError restitution_error(Integrator integrator, double divisor) {
  Params p;
  p.box = 20;
  p.integrator = integrator;
  p.dt_divisor = divisor;
  const Constants c = derive(p);
  const double r1 = 0.4, r2 = 0.6, v = 0.2 / c.tau_c;
  const double m1 = 4 * r1 * r1 / c.mean_d2, m2 = 4 * r2 * r2 / c.mean_d2, mb = m1 * m2 / (m1 + m2);
  const double omega = std::sqrt(c.kn / mb - 0.25 * c.gamma_n * c.gamma_n);
  const double exact = std::exp(-0.5 * c.gamma_n * std::numbers::pi / omega);
  RestitutionError out;
  const int phases = 32;
  for (int k = 0; k < phases; ++k) {
    const double gap = 0.2 + 2 * v * c.dt * k / phases;
    const std::vector<GrainInit> g = {{10 - r1 - gap / 2, 10, r1, v, 0, 0}, {10 + r2 + gap / 2, 10, r2, -v, 0, 0}};
    Simulation s = make_custom(p, g);
    const int steps = static_cast<int>(4 * divisor + 0.2 / (2 * v * c.dt));
    for (int n = 0; n < steps; ++n) step(s);
    const double err = std::abs(s.x[1][0] - s.x[1][1]) / c.dt / (2 * v) / exact - 1;
    out.mean += err / phases;
    out.worst = std::max(out.worst, std::abs(err));
  }
  out.mean = std::abs(out.mean);
  return out;
}

double energy_drift(Integrator integrator, double divisor) {
  Simulation s = make_lattice(scenes::elastic_gas(integrator, divisor));
  return scenes::worst_energy_drift(s, static_cast<int>(200 * divisor));
}

// A 2000-grain packing compressed to ρ = 0.80 (near jamming), then timed while compressing on.
Simulation dense_packing(Integrator integrator, double divisor) {
  Params p;
  p.compression_speed = 1e-2;
  p.relax_energy = 1e-4;
  p.rho_final = 0.80;
  p.frames = 2;
  Simulation s = make_lattice(p);
  RunOptions o;
  run(s, o);
  s.params.integrator = integrator;                    // switch integrator and step for the timing only
  const double ratio = s.params.dt_divisor / divisor;  // new Δt / old Δt: rescale Gear's scaled derivatives
  for (int k = 1; k < kGearOrder; ++k) {
    const double f = std::pow(ratio, k);
    for (auto* level : {&s.x[k], &s.y[k], &s.th[k]})
      for (double& v : *level) v *= f;
  }
  s.params.dt_divisor = divisor;
  s.c = derive(s.params);
  s.params.compression_speed = 1e-3;
  s.c.wall_speed = s.params.compression_speed / s.c.tau_c;
  s.walls_moving = true;
  return s;
}

double microseconds_per_step(Simulation s, int steps, Workers* workers = nullptr) {
  const auto t = Clock::now();
  for (int k = 0; k < steps; ++k) step(s, workers);
  return seconds_since(t) / steps * 1e6;
}

// Per-step cost on 1 and 2 threads (same bits either way) for a dense packing and a relaxing lattice.
void thread_table() {
  std::printf("\nThreads (2000 grains, Gear, tau/50; step() uses the team from 2 listed pairs per grain)\n");
  std::printf("%-34s %14s %14s %14s %10s\n", "state", "pairs/grain", "1 thread us", "2 threads us", "speed-up");
  Params lattice;
  Simulation fast = dense_packing(Integrator::gear, 50);  // compressed on at 10x the speed: deep overlaps
  fast.params.compression_speed = 1e-2;
  fast.c.wall_speed = fast.params.compression_speed / fast.c.tau_c;
  const std::pair<const char*, Simulation> states[] = {
      {"packing at rho 0.80, v_c = 1e-3", dense_packing(Integrator::gear, 50)},
      {"packing from rho 0.80, v_c = 1e-2", fast},
      {"fresh lattice, relaxing", make_lattice(lattice)}};
  Workers one(1), two(2);
  for (const auto& [name, state] : states) {
    const double pairs = static_cast<double>(state.list.partner.size()) / static_cast<double>(state.n);
    const double t1 = microseconds_per_step(state, 20000, &one), t2 = microseconds_per_step(state, 20000, &two);
    std::printf("%-34s %14.2f %14.1f %14.1f %9.2fx\n", name, pairs, t1, t2, t1 / t2);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t max_n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100000;
  const bool cost_only = argc > 2 && std::string(argv[2]) == "--cost-only";
  if (argc > 1 && std::string(argv[1]) == "--threads") {
    thread_table();
    return 0;
  }

  if (!cost_only) {
    std::printf(
        "Gear-4 vs velocity Verlet (restitution: 0.8-1.2 pair over 32 contact phases; energy: elastic\n"
        "frictionless gas of 400 grains over 200 tau_c; cost: 2000 grains at rho 0.80, per step)\n");
    std::printf("%-8s %-7s %14s %14s %14s %12s %16s\n", "method", "dt", "|mean e err|", "worst e err", "energy drift",
                "us/step", "us per tau_c");
    for (double divisor : {25.0, 50.0, 100.0}) {
      for (Integrator integrator : {Integrator::gear, Integrator::verlet}) {
        const RestitutionError e = restitution_error(integrator, divisor);
        const double drift = energy_drift(integrator, divisor);
        const double us = microseconds_per_step(dense_packing(integrator, divisor), 5000);
        char dt[32];
        std::snprintf(dt, sizeof dt, "tau/%g", divisor);
        std::printf("%-8s %-7s %14.3e %14.3e %14.3e %12.1f %16.0f\n", to_string(integrator), dt, e.mean, e.worst, drift,
                    us, us * divisor);
      }
    }
  }

  std::printf("\nCost against N (relaxing lattice at rho 0.63, Gear, tau/50)\n%10s %12s %16s %18s\n", "N", "steps/s",
              "particle-steps/s", "ns/particle-step");
  for (std::size_t n : {1000ul, 2000ul, 10000ul, 30000ul, 100000ul}) {
    if (n > max_n) break;
    Params p;
    p.particles = n;
    p.box = 50 * std::sqrt(static_cast<double>(n) / 2000);
    Simulation s = make_lattice(p);
    for (int k = 0; k < 200; ++k) step(s);  // let the lattice's overlaps resolve
    const int steps = static_cast<int>(std::max<std::size_t>(200, 4000000 / n));
    const auto t = Clock::now();
    for (int k = 0; k < steps; ++k) step(s);
    const double sec = seconds_since(t);
    std::printf("%10zu %12.0f %16.4g %18.1f\n", n, steps / sec, steps * static_cast<double>(n) / sec,
                sec / steps / static_cast<double>(n) * 1e9);
  }
  return 0;
}
