#include "server/sim/integrator.hpp"

#include <algorithm>

#include "server/sim/simulation.hpp"

namespace fnet::sim {
namespace {

struct Levels {
  double* __restrict v0;
  double* __restrict v1;
  double* __restrict v2;
  double* __restrict v3;
  double* __restrict v4;
};

Levels levels(std::array<std::vector<double>, kGearOrder>& a) {
  return {a[0].data(), a[1].data(), a[2].data(), a[3].data(), a[4].data()};
}

inline void predict(const Levels& q, std::size_t i) {
  const double a1 = q.v1[i], a2 = q.v2[i], a3 = q.v3[i], a4 = q.v4[i];
  q.v0[i] += a1 + a2 + a3 + a4;
  q.v1[i] = a1 + 2 * a2 + 3 * a3 + 4 * a4;
  q.v2[i] = a2 + 3 * a3 + 6 * a4;
  q.v3[i] = a3 + 4 * a4;
}

constexpr double kC0 = 19.0 / 120.0, kC1 = 3.0 / 4.0, kC3 = 1.0 / 2.0, kC4 = 1.0 / 12.0;

inline void correct(const Levels& q, std::size_t i, double accel_scaled) {
  const double delta = accel_scaled - q.v2[i];
  q.v0[i] += kC0 * delta;
  q.v1[i] += kC1 * delta;
  q.v2[i] = accel_scaled;
  q.v3[i] += kC3 * delta;
  q.v4[i] += kC4 * delta;
}

double max_displacement2(const Simulation& s) {
  const double* __restrict x = s.x[0].data();
  const double* __restrict y = s.y[0].data();
  const double* __restrict xb = s.list.x_build.data();
  const double* __restrict yb = s.list.y_build.data();
  double m = 0;
  for (std::size_t i = 0; i < s.n; ++i) {
    const double dx = x[i] - xb[i], dy = y[i] - yb[i];
    m = std::max(m, dx * dx + dy * dy);
  }
  return m;
}

}  // namespace

double gear_predict(Simulation& s) {
  const Levels qx = levels(s.x), qy = levels(s.y), qt = levels(s.th);
  for (std::size_t i = 0; i < s.n; ++i) predict(qx, i);
  for (std::size_t i = 0; i < s.n; ++i) predict(qy, i);
  for (std::size_t i = 0; i < s.n; ++i) predict(qt, i);
  return max_displacement2(s);
}

void gear_correct(Simulation& s) {
  const Levels qx = levels(s.x), qy = levels(s.y), qt = levels(s.th);
  const double h = 0.5 * s.c.dt * s.c.dt;  // a Δt² / 2 is the scaled second derivative
  const double* __restrict fx = s.fx.data();
  const double* __restrict fy = s.fy.data();
  const double* __restrict tq = s.torque.data();
  const double* __restrict im = s.inv_mass.data();
  const double* __restrict ii = s.inv_inertia.data();
  for (std::size_t i = 0; i < s.n; ++i) correct(qx, i, h * fx[i] * im[i]);
  for (std::size_t i = 0; i < s.n; ++i) correct(qy, i, h * fy[i] * im[i]);
  for (std::size_t i = 0; i < s.n; ++i) correct(qt, i, h * tq[i] * ii[i]);
}

// Scaled velocity v Δt gets a half kick of a Δt²/2; position moves by v Δt.
double verlet_first_half(Simulation& s) {
  const double h = 0.5 * s.c.dt * s.c.dt;
  double* __restrict x0 = s.x[0].data();
  double* __restrict x1 = s.x[1].data();
  double* __restrict y0 = s.y[0].data();
  double* __restrict y1 = s.y[1].data();
  double* __restrict t0 = s.th[0].data();
  double* __restrict t1 = s.th[1].data();
  const double* __restrict im = s.inv_mass.data();
  const double* __restrict ii = s.inv_inertia.data();
  for (std::size_t i = 0; i < s.n; ++i) {
    x1[i] += h * s.fx[i] * im[i];
    y1[i] += h * s.fy[i] * im[i];
    t1[i] += h * s.torque[i] * ii[i];
    x0[i] += x1[i];
    y0[i] += y1[i];
    t0[i] += t1[i];
  }
  return max_displacement2(s);
}

void verlet_second_half(Simulation& s) {
  const double h = 0.5 * s.c.dt * s.c.dt;
  double* __restrict x1 = s.x[1].data();
  double* __restrict y1 = s.y[1].data();
  double* __restrict t1 = s.th[1].data();
  const double* __restrict im = s.inv_mass.data();
  const double* __restrict ii = s.inv_inertia.data();
  for (std::size_t i = 0; i < s.n; ++i) {
    x1[i] += h * s.fx[i] * im[i];
    y1[i] += h * s.fy[i] * im[i];
    t1[i] += h * s.torque[i] * ii[i];
  }
}

}  // namespace fnet::sim
