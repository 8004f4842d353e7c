#include "server/dem/integrator.hpp"

#include <atomic>
#include <cstddef>

#include "server/dem/clones.hpp"
#include "server/dem/run_state.hpp"
#include "server/dem/workers.hpp"

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
[[gnu::noinline]] FNET_SIM_CLONES bool predict_all(double* __restrict x0, double* __restrict x1, double* __restrict x2,
                                                   double* __restrict x3, const double* __restrict x4,
                                                   double* __restrict y0, double* __restrict y1, double* __restrict y2,
                                                   double* __restrict y3, const double* __restrict y4,
                                                   double* __restrict t0, double* __restrict t1, double* __restrict t2,
                                                   double* __restrict t3, const double* __restrict t4,
                                                   const double* __restrict xb, const double* __restrict yb,
                                                   double limit2, std::size_t n) {
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

[[gnu::noinline]] FNET_SIM_CLONES void correct_all(double* __restrict x0, double* __restrict x1, double* __restrict x2,
                                                   double* __restrict x3, double* __restrict x4, double* __restrict y0,
                                                   double* __restrict y1, double* __restrict y2, double* __restrict y3,
                                                   double* __restrict y4, double* __restrict t0, double* __restrict t1,
                                                   double* __restrict t2, double* __restrict t3, double* __restrict t4,
                                                   const double* __restrict fx, const double* __restrict fy,
                                                   const double* __restrict tq, const double* __restrict im,
                                                   const double* __restrict ii, double h, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    correct(x0, x1, x2, x3, x4, i, h * fx[i] * im[i]);
    correct(y0, y1, y2, y3, y4, i, h * fy[i] * im[i]);
    correct(t0, t1, t2, t3, t4, i, h * tq[i] * ii[i]);
  }
}

// One pass over the grains predicts x, y and θ (the same arithmetic as three separate passes, so
// the same bits) and checks the displacement since the last list build.
}  // namespace

// Grains [b, e) only: the loops are element-wise, so a team splits them without changing a bit.
bool gear_predict_range(Simulation& s, double limit2, std::size_t b, std::size_t e) {
  auto& x = s.x;
  auto& y = s.y;
  auto& t = s.th;
  return predict_all(x[0].data() + b, x[1].data() + b, x[2].data() + b, x[3].data() + b, x[4].data() + b,
                     y[0].data() + b, y[1].data() + b, y[2].data() + b, y[3].data() + b, y[4].data() + b,
                     t[0].data() + b, t[1].data() + b, t[2].data() + b, t[3].data() + b, t[4].data() + b,
                     s.list.x_build.data() + b, s.list.y_build.data() + b, limit2, e - b);
}

void gear_correct_range(Simulation& s, std::size_t b, std::size_t e) {
  auto& x = s.x;
  auto& y = s.y;
  auto& t = s.th;
  const double h = 0.5 * s.c.dt * s.c.dt;  // a Δt² / 2 is the scaled second derivative
  correct_all(x[0].data() + b, x[1].data() + b, x[2].data() + b, x[3].data() + b, x[4].data() + b, y[0].data() + b,
              y[1].data() + b, y[2].data() + b, y[3].data() + b, y[4].data() + b, t[0].data() + b, t[1].data() + b,
              t[2].data() + b, t[3].data() + b, t[4].data() + b, s.fx.data() + b, s.fy.data() + b, s.torque.data() + b,
              s.inv_mass.data() + b, s.inv_inertia.data() + b, h, e - b);
}

// A team splits the grains in equal shares (the corrector runs with the force sum,
// compute_forces' `then`).
bool gear_predict(Simulation& s, double limit2, Workers* workers) {
  if (!workers || workers->size() == 1) return gear_predict_range(s, limit2, 0, s.n);
  const unsigned parts = workers->size();
  std::atomic<bool> moved{false};
  workers->run([&](unsigned part) {
    if (gear_predict_range(s, limit2, share_begin(s.n, part, parts), share_begin(s.n, part + 1, parts)))
      moved.store(true, std::memory_order_relaxed);
  });
  return moved.load();
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
