#include "server/sim/contact_forces.hpp"

#include <algorithm>
#include <cmath>

#include "server/sim/clones.hpp"
#include "server/sim/simulation.hpp"

namespace fnet::sim {

// Cloned for AVX2 (clones.hpp): the same bits, fewer instructions.
FNET_SIM_CLONES void compute_forces(Simulation& s) {
  const std::size_t n = s.n;
  double* __restrict fx = s.fx.data();
  double* __restrict fy = s.fy.data();
  double* __restrict tq = s.torque.data();
  std::fill(s.fx.begin(), s.fx.end(), 0.0);
  std::fill(s.fy.begin(), s.fy.end(), 0.0);
  std::fill(s.torque.begin(), s.torque.end(), 0.0);

  const double* __restrict px = s.x[0].data();
  const double* __restrict py = s.y[0].data();
  const double* __restrict vx = s.x[1].data();  // velocities × Δt
  const double* __restrict vy = s.y[1].data();
  const double* __restrict w = s.th[1].data();
  const double* __restrict rad = s.radius.data();

  NeighbourList& l = s.list;
  const std::uint32_t* __restrict offset = l.offset.data();
  const std::uint32_t* __restrict partner = l.partner.data();
  double* __restrict hx = l.hx.data();
  double* __restrict hy = l.hy.data();
  double* __restrict pfn = l.fn.data();
  double* __restrict pft2 = l.ft2.data();
  const double* __restrict pmeff = l.meff.data();
  std::uint8_t* __restrict touching = l.touching.data();

  const double dt = s.c.dt, inv_dt = 1.0 / dt;
  const double kn = s.c.kn, kt = s.c.kt, inv_kt = kt > 0 ? 1.0 / kt : 0.0;
  const double gamma = s.c.gamma_n;
  const double mu = s.params.mu;

  for (std::size_t i = 0; i < n; ++i) {
    const double xi = px[i], yi = py[i], ri = rad[i], vxi = vx[i], vyi = vy[i], wi = w[i];
    double fxi = 0, fyi = 0, ti = 0;
    for (std::uint32_t p = offset[i]; p < offset[i + 1]; ++p) {
      const std::uint32_t j = partner[p];
      const double dx = xi - px[j], dy = yi - py[j];
      const double rsq = dx * dx + dy * dy, rsum = ri + rad[j];
      if (rsq >= rsum * rsum) {
        if (touching[p]) {  // the contact just ended: its spring goes
          touching[p] = 0;
          hx[p] = hy[p] = pfn[p] = pft2[p] = 0;
        }
        continue;
      }
      const double rinv = 1.0 / std::sqrt(rsq);
      const double nx = dx * rinv, ny = dy * rinv;
      const double overlap = rsum - rsq * rinv;
      const double rj = rad[j];
      const double dvx = (vxi - vx[j]) * inv_dt, dvy = (vyi - vy[j]) * inv_dt;
      const double wr = (ri * wi + rj * w[j]) * inv_dt;
      const double vn = dvx * nx + dvy * ny;
      const double vtx = dvx - vn * nx + wr * ny;
      const double vty = dvy - vn * ny - wr * nx;
      const double meff = pmeff[p];
      const double fn = kn * overlap - gamma * meff * vn;

      double sx = hx[p] + vtx * dt, sy = hy[p] + vty * dt;
      const double sn = sx * nx + sy * ny;
      sx -= sn * nx;
      sy -= sn * ny;
      double ftx = -kt * sx - gamma * meff * vtx;
      double fty = -kt * sy - gamma * meff * vty;
      double ft2 = ftx * ftx + fty * fty;
      const double fmax = mu * std::abs(fn);
      if (ft2 > fmax * fmax) {
        const double scale = fmax / std::sqrt(ft2);
        ftx *= scale;
        fty *= scale;
        ft2 = fmax * fmax;
        sx = -(ftx + gamma * meff * vtx) * inv_kt;
        sy = -(fty + gamma * meff * vty) * inv_kt;
      }
      hx[p] = sx;
      hy[p] = sy;
      pfn[p] = fn;
      pft2[p] = ft2;
      touching[p] = 1;

      const double cfx = fn * nx + ftx, cfy = fn * ny + fty;
      const double tz = nx * fty - ny * ftx;
      fxi += cfx;
      fyi += cfy;
      ti -= ri * tz;
      fx[j] -= cfx;
      fy[j] -= cfy;
      tq[j] -= rj * tz;
    }
    fx[i] += fxi;
    fy[i] += fyi;
    tq[i] += ti;
  }
}

}  // namespace fnet::sim
