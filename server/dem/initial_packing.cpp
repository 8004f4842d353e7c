#include "server/dem/initial_packing.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "server/dem/contact_forces.hpp"
#include "server/dem/rng.hpp"
#include "server/dem/walls.hpp"

namespace fnet::sim {
namespace {

Simulation make(const Params& p, std::span<const GrainInit> grains) {
  validate(p);
  if (!p.box) throw std::invalid_argument("invalid parameter box: a hand-placed scene needs one");
  Simulation s;
  s.params = p;
  s.c = derive(p);
  s.n = grains.size();
  double r_max = 0;
  for (const GrainInit& g : grains) {
    const double d = 2 * g.r;
    const double m = d * d / s.c.mean_d2;  // mass ∝ area, mean 1 over the diameter distribution
    s.radius.push_back(g.r);
    s.inv_mass.push_back(1 / m);
    s.inv_inertia.push_back(1 / (0.5 * m * g.r * g.r));  // a disk
    s.grain_area += std::numbers::pi * g.r * g.r;
    r_max = std::max(r_max, g.r);
  }
  add_walls(s);
  const std::size_t bodies = s.n + s.nw;
  for (int k = 0; k < kGearOrder; ++k) {
    const std::size_t size = k < 2 ? bodies : s.n;
    s.x[k].assign(size, 0.0);
    s.y[k].assign(size, 0.0);
    s.th[k].assign(size, 0.0);
  }
  s.fx.assign(bodies, 0.0);
  s.fy.assign(bodies, 0.0);
  s.torque.assign(bodies, 0.0);
  for (std::size_t i = 0; i < s.n; ++i) {
    s.x[0][i] = grains[i].x;
    s.y[0][i] = grains[i].y;
    s.x[1][i] = grains[i].vx * s.c.dt;
    s.y[1][i] = grains[i].vy * s.c.dt;
    s.th[1][i] = grains[i].w * s.c.dt;
  }
  const double dw = p.wall_diameter;
  const double margin = dw + p.skin + 2.0;  // room for grains pressed into the wall rows
  setup_grid(s.list, -margin, *p.box + margin, std::max(2 * r_max, dw), p.skin);
  place_walls(s);
  rebuild(s.list, s.x[0], s.y[0], s.radius, s.inv_mass, s.n, wall_offset(s));

  // Start Gear (and Verlet) from the accelerations of the initial forces; the springs of
  // initially overlapping pairs start from zero.
  compute_forces(s);
  const double h = 0.5 * s.c.dt * s.c.dt;
  for (std::size_t i = 0; i < s.n; ++i) {
    s.x[2][i] = h * s.fx[i] * s.inv_mass[i];
    s.y[2][i] = h * s.fy[i] * s.inv_mass[i];
    s.th[2][i] = h * s.torque[i] * s.inv_inertia[i];
  }
  std::fill(s.list.hx.begin(), s.list.hx.end(), 0.0);
  std::fill(s.list.hy.begin(), s.list.hy.end(), 0.0);
  return s;
}

}  // namespace

Simulation make_lattice(const Params& p) {
  validate(p);
  const Constants c = derive(p);
  Rng rng(p.seed);
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(p.particles))));
  const double v0 = p.initial_speed / c.tau_c;  // d/τ_c to internal units
  std::vector<GrainInit> grains(p.particles);
  double area = 0;
  for (GrainInit& g : grains) {
    g.r = 0.5 * (1 + p.polydispersity * (rng.uniform() - 0.5));
    const double angle = 2 * std::numbers::pi * rng.uniform();
    const double speed = v0 * std::sqrt(rng.uniform());  // uniform in a disk of radius v0
    g.vx = speed * std::cos(angle);
    g.vy = speed * std::sin(angle);
    area += std::numbers::pi * g.r * g.r;
  }
  // The box holds the grains drawn at rho_initial, unless it is given.
  Params q = p;
  if (!q.box) q.box = std::sqrt(area / q.rho_initial);
  const double rho0 = area / (*q.box * *q.box);
  if (p.box) q.rho_initial = rho0;  // what the given box makes of it, so that the recorded parameters agree
  const double a = *q.box / static_cast<double>(side);
  const auto text = [](double v) {
    char buf[32];
    return std::string(buf, std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 6).ptr);
  };
  if (a < 1.0)
    throw std::invalid_argument("invalid parameter box (--box, --rho-initial): a side of " + text(*q.box) + " d puts " +
                                std::to_string(p.particles) +
                                " grains on a square lattice closer than d_ave (start at a lower density)");
  if (q.rho_final <= rho0)
    throw std::invalid_argument("invalid parameter rho_final (--rho-final): " + text(q.rho_final) +
                                " is not above the start's packing fraction " + text(rho0));
  for (std::size_t i = 0; i < grains.size(); ++i) {
    grains[i].x = (static_cast<double>(i % side) + 0.5) * a;
    grains[i].y = (static_cast<double>(i / side) + 0.5) * a;
  }
  return make(q, grains);
}

Simulation make_custom(const Params& p, std::span<const GrainInit> grains) {
  Params q = p;
  q.particles = grains.size();
  return make(q, grains);
}

}  // namespace fnet::sim
