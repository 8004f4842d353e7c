#include "tests/support/fcc_packing.hpp"

#include <cmath>
#include <string>

namespace fnet::testing {
namespace {

// splitmix64: a few lines, the same numbers everywhere.
class Jitter {
 public:
  explicit Jitter(std::uint64_t seed) : state_(seed) {}
  // Uniform in [-1, 1).
  double next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-52 - 1.0;
  }

 private:
  std::uint64_t state_;
};

}  // namespace

Frame fcc_frame(const FccOptions& o) {
  static constexpr double kBasis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  const double a = o.spacing * std::sqrt(2.0);  // the cubic cell's side
  Jitter jitter(o.seed);
  Frame f;
  f.label = "fcc " + std::to_string(o.cells) + "^3";
  f.dimension = 3;
  for (int cz = 0; cz < o.cells; ++cz)
    for (int cy = 0; cy < o.cells; ++cy)
      for (int cx = 0; cx < o.cells; ++cx)
        for (const auto& b : kBasis) {
          Particle p;
          p.x = a * (cx + b[0]) + o.jitter * jitter.next();
          p.y = a * (cy + b[1]) + o.jitter * jitter.next();
          p.z = a * (cz + b[2]) + o.jitter * jitter.next();
          p.r = o.radius;
          f.particles.push_back(p);
        }
  f.particle_count = f.particles.size();
  for (std::size_t i = 0; i < f.particles.size(); ++i)
    for (std::size_t j = i + 1; j < f.particles.size(); ++j) {
      const Particle &p = f.particles[i], &q = f.particles[j];
      const double overlap = p.r + q.r - std::hypot(p.x - q.x, p.y - q.y, p.z - q.z);
      if (!(overlap > 0)) continue;
      // Rounded to 1e-3: a few forces tie exactly, as in real data.
      const double fn = std::round(1e6 * overlap) / 1e3;
      const double share = 0.1 + 0.1 * static_cast<double>((7 * i + 13 * j) % 5);
      f.contacts.push_back({static_cast<std::int64_t>(i), static_cast<std::int64_t>(j), fn, share * fn});
    }
  return f;
}

}  // namespace fnet::testing
