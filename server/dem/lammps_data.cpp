#include "server/dem/lammps_data.hpp"

#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace fnet::sim {

void write_lammps_data(const Simulation& s, const std::filesystem::path& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error(path.string() + ": cannot open for writing");
  const double margin = s.params.wall_diameter + 3;
  std::fprintf(f, "fnet-simd state at step %lld (seed %llu)\n\n", static_cast<long long>(s.step),
               static_cast<unsigned long long>(s.params.seed));
  std::fprintf(f, "%zu atoms\n5 atom types\n\n", s.n + s.nw);
  std::fprintf(f, "%.17g %.17g xlo xhi\n%.17g %.17g ylo yhi\n-0.5 0.5 zlo zhi\n\n", -margin,
               s.params.box.value() + margin, -margin, s.params.box.value() + margin);
  std::fprintf(f, "Atoms # sphere\n\n");
  const double sphere = 4.0 / 3.0 * std::numbers::pi;
  for (std::size_t b = 0; b < s.n + s.nw; ++b) {
    const bool grain = b < s.n;
    const double r = s.radius[b];
    const double mass = grain ? 1 / s.inv_mass[b] : 1e12;
    const int type = grain ? 1 : 2 + s.wall_side[b - s.n];
    std::fprintf(f, "%zu %d %.17g %.17g %.17g %.17g 0\n", b + 1, type, 2 * r, mass / (sphere * r * r * r), s.x[0][b],
                 s.y[0][b]);
  }
  std::fprintf(f, "\nVelocities\n\n");
  const double inv_dt = 1 / s.c.dt;
  for (std::size_t b = 0; b < s.n + s.nw; ++b) {
    const bool grain = b < s.n;
    std::fprintf(f, "%zu %.17g %.17g 0 0 0 %.17g\n", b + 1, grain ? s.x[1][b] * inv_dt : 0.0,
                 grain ? s.y[1][b] * inv_dt : 0.0, grain ? s.th[1][b] * inv_dt : 0.0);
  }
  if (std::fclose(f) != 0) throw std::runtime_error(path.string() + ": write failed");
}

}  // namespace fnet::sim
