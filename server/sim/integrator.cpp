#include "server/sim/integrator.hpp"

#include <cstddef>

#include "server/sim/clones.hpp"
#include "server/sim/simulation.hpp"

namespace fnet::sim {
namespace {

// The Taylor (Pascal-triangle) predictor of one coordinate.
inline void predict(double* __restrict v0, double* __restrict v1, double* __restrict v2, double* __restrict v3,
                    const double* __restrict v4, std::size_t i) {
  const double a1 = v1[i], a2 = v2[i], a3 = v3[i], a4 = v4[i];
  v0[i] += a1 + a2 + a3 + a4;
  v1[i] = a1 + 2 * a2 + 3 * a3 + 4 * a4;
  v2[i] = a2 + 3 * a3 + 6 * a4;
  v3[i] = a3 + 4 * a4;
}

constexpr double kC0 = 19.0 / 120.0, kC1 = 3.0 / 4.0, kC3 = 1.0 / 2.0, kC4 = 1.0 / 12.0;

inline void correct(double* __restrict v0, double* __restrict v1, double* __restrict v2, double* __restrict v3,
                    double* __restrict v4, std::size_t i, double accel_scaled) {
  const double delta = accel_scaled - v2[i];
  v0[i] += kC0 * delta;
  v1[i] += kC1 * delta;
  v2[i] = accel_scaled;
  v3[i] += kC3 * delta;
  v4[i] += kC4 * delta;
}

bool moved_beyond(const Simulation& s, double limit2) {
  const double* __restrict x = s.x[0].data();
  const double* __restrict y = s.y[0].data();
  const double* __restrict xb = s.list.x_build.data();
  const double* __restrict yb = s.list.y_build.data();
  int moved = 0;
  for (std::size_t i = 0; i < s.n; ++i) {
    const double dx = x[i] - xb[i], dy = y[i] - yb[i];
    moved |= dx * dx + dy * dy > limit2;
  }
  return moved != 0;
}

// The fused loops take their arrays as restrict parameters: GCC honours restrict on parameters
// (not on local pointers), and then vectorizes.
[[gnu::noinline]] FNET_SIM_CLONES bool predict_all(
    double* __restrict x0, double* __restrict x1, double* __restrict x2, double* __restrict x3,
    const double* __restrict x4, double* __restrict y0, double* __restrict y1, double* __restrict y2,
    double* __restrict y3, const double* __restrict y4, double* __restrict t0, double* __restrict t1,
    double* __restrict t2, double* __restrict t3, const double* __restrict t4, const double* __restrict xb,
    const double* __restrict yb, double limit2, std::size_t n) {
  int moved = 0;  // an OR of comparisons (not a max) so that the loop vectorizes
  for (std::size_t i = 0; i < n; ++i) {
    predict(x0, x1, x2, x3, x4, i);
    predict(y0, y1, y2, y3, y4, i);
    predict(t0, t1, t2, t3, t4, i);
    const double dx = x0[i] - xb[i], dy = y0[i] - yb[i];
    moved |= dx * dx + dy * dy > limit2;
  }
  return moved != 0;
}

[[gnu::noinline]] FNET_SIM_CLONES void correct_all(double* __restrict x0, double* __restrict x1, double* __restrict x2, double* __restrict x3,
                 double* __restrict x4, double* __restrict y0, double* __restrict y1, double* __restrict y2,
                 double* __restrict y3, double* __restrict y4, double* __restrict t0, double* __restrict t1,
                 double* __restrict t2, double* __restrict t3, double* __restrict t4, const double* __restrict fx,
                 const double* __restrict fy, const double* __restrict tq, const double* __restrict im,
                 const double* __restrict ii, double h, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    correct(x0, x1, x2, x3, x4, i, h * fx[i] * im[i]);
    correct(y0, y1, y2, y3, y4, i, h * fy[i] * im[i]);
    correct(t0, t1, t2, t3, t4, i, h * tq[i] * ii[i]);
  }
}

}  // namespace

// One pass over the grains predicts x, y and θ (the same arithmetic as three separate passes, so
// the same bits) and checks the displacement since the last list build.
bool gear_predict(Simulation& s, double limit2) {
  auto& x = s.x;
  auto& y = s.y;
  auto& t = s.th;
  return predict_all(x[0].data(), x[1].data(), x[2].data(), x[3].data(), x[4].data(), y[0].data(), y[1].data(),
                     y[2].data(), y[3].data(), y[4].data(), t[0].data(), t[1].data(), t[2].data(), t[3].data(),
                     t[4].data(), s.list.x_build.data(), s.list.y_build.data(), limit2, s.n);
}

void gear_correct(Simulation& s) {
  auto& x = s.x;
  auto& y = s.y;
  auto& t = s.th;
  const double h = 0.5 * s.c.dt * s.c.dt;  // a Δt² / 2 is the scaled second derivative
  correct_all(x[0].data(), x[1].data(), x[2].data(), x[3].data(), x[4].data(), y[0].data(), y[1].data(), y[2].data(),
              y[3].data(), y[4].data(), t[0].data(), t[1].data(), t[2].data(), t[3].data(), t[4].data(), s.fx.data(),
              s.fy.data(), s.torque.data(), s.inv_mass.data(), s.inv_inertia.data(), h, s.n);
}

// Half kick: the scaled velocity v Δt gains a Δt²/2.
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

// A half kick, then the position moves by v Δt.
bool verlet_first_half(Simulation& s, double limit2) {
  verlet_second_half(s);
  double* __restrict x0 = s.x[0].data();
  double* __restrict y0 = s.y[0].data();
  double* __restrict t0 = s.th[0].data();
  const double* __restrict x1 = s.x[1].data();
  const double* __restrict y1 = s.y[1].data();
  const double* __restrict t1 = s.th[1].data();
  for (std::size_t i = 0; i < s.n; ++i) {
    x0[i] += x1[i];
    y0[i] += y1[i];
    t0[i] += t1[i];
  }
  return moved_beyond(s, limit2);
}

}  // namespace fnet::sim
