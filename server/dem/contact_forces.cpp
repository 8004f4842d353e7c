#include "server/dem/contact_forces.hpp"

#include <algorithm>
#include <cmath>

#include "server/dem/clones.hpp"
#include "server/dem/run_state.hpp"
#include "server/dem/workers.hpp"

namespace fnet::sim {

namespace {

struct Law {
  double dt, inv_dt, kn, kt, inv_kt, gamma, mu;
  explicit Law(const Simulation& s)
      : dt(s.c.dt),
        inv_dt(1.0 / s.c.dt),
        kn(s.c.kn),
        kt(s.c.kt),
        inv_kt(s.c.kt > 0 ? 1.0 / s.c.kt : 0.0),
        gamma(s.c.gamma_n),
        mu(s.params.mu) {}
};

// What the pair loops read: positions, velocities × Δt, spins × Δt, radii, and the list.
struct Bodies {
  const double *px, *py, *vx, *vy, *w, *rad;
  const std::uint32_t *offset, *partner;
  explicit Bodies(const Simulation& s)
      : px(s.x[0].data()),
        py(s.y[0].data()),
        vx(s.x[1].data()),
        vy(s.y[1].data()),
        w(s.th[1].data()),
        rad(s.radius.data()),
        offset(s.list.offset.data()),
        partner(s.list.partner.data()) {}
};

// The force of pair p between grain i and body j: updates the pair's history and records, and
// returns false when the surfaces do not touch. Out: the force on i (j gets the opposite) and
// tz, the torque term (i gets -r_i tz, j gets -r_j tz). One definition for the serial and the
// threaded loops, so both give the same bits.
[[gnu::always_inline]] inline bool pair_force(const Law& law, NeighbourList& l, std::uint32_t p, double xi, double yi,
                                              double ri, double vxi, double vyi, double wi, double xj, double yj,
                                              double rj, double vxj, double vyj, double wj, double& cfx, double& cfy,
                                              double& tz) {
  const double dx = xi - xj, dy = yi - yj;
  const double rsq = dx * dx + dy * dy, rsum = ri + rj;
  if (rsq >= rsum * rsum) {
    if (l.touching[p]) {  // the contact just ended: its spring goes
      l.touching[p] = 0;
      l.hx[p] = l.hy[p] = l.fn[p] = l.ft2[p] = 0;
    }
    return false;
  }
  const double dt = law.dt, inv_dt = law.inv_dt, kn = law.kn, kt = law.kt, gamma = law.gamma;
  const double rinv = 1.0 / std::sqrt(rsq);
  const double nx = dx * rinv, ny = dy * rinv;
  const double overlap = rsum - rsq * rinv;
  const double dvx = (vxi - vxj) * inv_dt, dvy = (vyi - vyj) * inv_dt;
  const double wr = (ri * wi + rj * wj) * inv_dt;
  const double vn = dvx * nx + dvy * ny;
  const double vtx = dvx - vn * nx + wr * ny;
  const double vty = dvy - vn * ny - wr * nx;
  const double meff = l.meff[p];
  const double fn = kn * overlap - gamma * meff * vn;

  double sx = l.hx[p] + vtx * dt, sy = l.hy[p] + vty * dt;
  const double sn = sx * nx + sy * ny;
  sx -= sn * nx;
  sy -= sn * ny;
  double ftx = -kt * sx - gamma * meff * vtx;
  double fty = -kt * sy - gamma * meff * vty;
  double ft2 = ftx * ftx + fty * fty;
  const double fmax = law.mu * std::abs(fn);
  if (ft2 > fmax * fmax) {
    const double scale = fmax / std::sqrt(ft2);
    ftx *= scale;
    fty *= scale;
    ft2 = fmax * fmax;
    sx = -(ftx + gamma * meff * vtx) * law.inv_kt;
    sy = -(fty + gamma * meff * vty) * law.inv_kt;
  }
  l.hx[p] = sx;
  l.hy[p] = sy;
  l.fn[p] = fn;
  l.ft2[p] = ft2;
  l.touching[p] = 1;
  cfx = fn * nx + ftx;
  cfy = fn * ny + fty;
  tz = nx * fty - ny * ftx;
  return true;
}

// Cloned for AVX2 (clones.hpp): the same bits, fewer instructions.
FNET_SIM_CLONES void serial_forces(Simulation& s) {
  const std::size_t n = s.n;
  double* __restrict fx = s.fx.data();
  double* __restrict fy = s.fy.data();
  double* __restrict tq = s.torque.data();
  std::fill(s.fx.begin(), s.fx.end(), 0.0);
  std::fill(s.fy.begin(), s.fy.end(), 0.0);
  std::fill(s.torque.begin(), s.torque.end(), 0.0);

  const Bodies b(s);
  NeighbourList& l = s.list;
  const Law law(s);

  for (std::size_t i = 0; i < n; ++i) {
    const double xi = b.px[i], yi = b.py[i], ri = b.rad[i], vxi = b.vx[i], vyi = b.vy[i], wi = b.w[i];
    double fxi = 0, fyi = 0, ti = 0;
    for (std::uint32_t p = b.offset[i]; p < b.offset[i + 1]; ++p) {
      const std::uint32_t j = b.partner[p];
      const double rj = b.rad[j];
      double cfx, cfy, tz;
      if (!pair_force(law, l, p, xi, yi, ri, vxi, vyi, wi, b.px[j], b.py[j], rj, b.vx[j], b.vy[j], b.w[j], cfx, cfy,
                      tz))
        continue;
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

// Threaded, first pass: the pairs of grains [begin, end), each force stored with its pair.
FNET_SIM_CLONES void pair_pass(Simulation& s, std::size_t begin, std::size_t end) {
  const Bodies b(s);
  NeighbourList& l = s.list;
  double* __restrict cfx = l.cfx.data();
  double* __restrict cfy = l.cfy.data();
  double* __restrict ctz = l.ctz.data();
  const Law law(s);
  for (std::size_t i = begin; i < end; ++i) {
    const double xi = b.px[i], yi = b.py[i], ri = b.rad[i], vxi = b.vx[i], vyi = b.vy[i], wi = b.w[i];
    for (std::uint32_t p = b.offset[i]; p < b.offset[i + 1]; ++p) {
      const std::uint32_t j = b.partner[p];
      pair_force(law, l, p, xi, yi, ri, vxi, vyi, wi, b.px[j], b.py[j], b.rad[j], b.vx[j], b.vy[j], b.w[j], cfx[p],
                 cfy[p], ctz[p]);
    }
  }
}

// Threaded, second pass: each body [begin, end) sums its pairs in the serial loop's order (as the
// partner, pair by pair in increasing order, then its own pairs as one subtotal).
FNET_SIM_CLONES void gather_pass(Simulation& s, std::size_t begin, std::size_t end) {
  const NeighbourList& l = s.list;
  const std::uint32_t* __restrict offset = l.offset.data();
  const std::uint32_t* __restrict in_offset = l.in_offset.data();
  const std::uint32_t* __restrict in_pair = l.in_pair.data();
  const std::uint8_t* __restrict touching = l.touching.data();
  const double* __restrict cfx = l.cfx.data();
  const double* __restrict cfy = l.cfy.data();
  const double* __restrict ctz = l.ctz.data();
  const double* __restrict rad = s.radius.data();
  double* __restrict fx = s.fx.data();
  double* __restrict fy = s.fy.data();
  double* __restrict tq = s.torque.data();
  for (std::size_t b = begin; b < end; ++b) {
    const double r = rad[b];
    double f_x = 0, f_y = 0, t = 0;
    for (std::uint32_t k = in_offset[b]; k < in_offset[b + 1]; ++k) {
      const std::uint32_t p = in_pair[k];
      if (!touching[p]) continue;
      f_x -= cfx[p];
      f_y -= cfy[p];
      t -= r * ctz[p];
    }
    if (b < s.n) {
      double fxi = 0, fyi = 0, ti = 0;
      for (std::uint32_t p = offset[b]; p < offset[b + 1]; ++p) {
        if (!touching[p]) continue;
        fxi += cfx[p];
        fyi += cfy[p];
        ti -= r * ctz[p];
      }
      f_x += fxi;
      f_y += fyi;
      t += ti;
    }
    fx[b] = f_x;
    fy[b] = f_y;
    tq[b] = t;
  }
}

}  // namespace

void compute_forces(Simulation& s, Workers* workers, const GrainsDone& then) {
  if (!workers || workers->size() == 1) {
    serial_forces(s);
    if (then) then(0, s.n);
    return;
  }
  NeighbourList& l = s.list;
  const std::size_t pairs = l.partner.size();
  l.cfx.resize(pairs);
  l.cfy.resize(pairs);
  l.ctz.resize(pairs);
  const unsigned parts = workers->size();
  const std::size_t bodies = s.fx.size();
  // Rows split by their pair counts, bodies in equal shares.
  const auto row_split = [&](unsigned part) -> std::size_t {
    if (part == 0) return 0;
    if (part == parts) return s.n;
    const std::uint32_t target = static_cast<std::uint32_t>(pairs * part / parts);
    return static_cast<std::size_t>(
        std::lower_bound(l.offset.begin(), l.offset.begin() + static_cast<std::ptrdiff_t>(s.n), target) -
        l.offset.begin());
  };
  workers->run([&](unsigned part) { pair_pass(s, row_split(part), row_split(part + 1)); });
  workers->run([&](unsigned part) {
    const std::size_t begin = share_begin(bodies, part, parts), end = share_begin(bodies, part + 1, parts);
    gather_pass(s, begin, end);
    if (then && begin < s.n) then(begin, std::min(end, s.n));
  });
}

}  // namespace fnet::sim
