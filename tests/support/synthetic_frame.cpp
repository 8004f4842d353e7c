#include "tests/support/synthetic_frame.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace fnet::testing {
namespace {

// splitmix64: tiny, fast and identical everywhere, unlike std::*_distribution.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 0x1234567ull) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(uniform() * static_cast<double>(n)); }

 private:
  std::uint64_t state_;
};

constexpr double kSpacing = 0.935;  // tuned with kJitter for mean degree ~4.2
constexpr double kJitter = 0.087;   // half-width of the uniform jitter (sd ~0.05)
constexpr double kMinRadius = 0.4, kMaxRadius = 0.6;
constexpr double kReach = 2 * kMaxRadius;  // no contact is longer than this

std::vector<Particle> place_particles(const SyntheticOptions& opt, Rng& rng) {
  const std::size_t n = opt.particles;
  const auto interstitials =
      std::min(n / 4, static_cast<std::size_t>(std::llround(opt.interstitial_fraction * static_cast<double>(n))));
  const std::size_t sites = n - interstitials;
  const auto cols = std::max<std::size_t>(
      2, static_cast<std::size_t>(std::llround(std::sqrt(static_cast<double>(sites) * 2 / std::sqrt(3.0)))));
  const double row_height = kSpacing * std::sqrt(3.0) / 2;

  std::vector<Particle> at(n);
  for (std::size_t k = 0; k < sites; ++k) {
    const std::size_t r = k / cols, c = k % cols;
    at[k].x =
        (static_cast<double>(c) + 0.5 * static_cast<double>(r % 2)) * kSpacing + kJitter * (2 * rng.uniform() - 1);
    at[k].y = static_cast<double>(r) * row_height + kJitter * (2 * rng.uniform() - 1);
  }
  // An interstitial sits at the centroid of an upward lattice triangle (site, right, upper).
  for (std::size_t k = sites; k < n; ++k) {
    std::size_t s = 0, right = 0, upper = 0;
    do {
      s = rng.below(sites);
      const std::size_t r = s / cols, c = s % cols;
      right = s + 1;
      upper = (r + 1) * cols + c + (r % 2);
      if (c + 1 < cols && upper < sites) break;
    } while (true);
    at[k].x = (at[s].x + at[right].x + at[upper].x) / 3;
    at[k].y = (at[s].y + at[right].y + at[upper].y) / 3;
  }
  for (Particle& p : at) p.r = kMinRadius + (kMaxRadius - kMinRadius) * rng.uniform();

  // Ids unrelated to position, as in a simulator after the grains have mixed.
  std::vector<std::uint32_t> id(n);
  for (std::size_t k = 0; k < n; ++k) id[k] = static_cast<std::uint32_t>(k);
  for (std::size_t k = n; k > 1; --k) std::swap(id[k - 1], id[rng.below(k)]);
  std::vector<Particle> particles(n);
  for (std::size_t k = 0; k < n; ++k) particles[id[k]] = at[k];
  return particles;
}

// Overlapping pairs by grid hashing with cells as wide as the longest possible contact.
std::vector<Contact> find_contacts(const std::vector<Particle>& p) {
  std::vector<Contact> contacts;
  if (p.empty()) return contacts;
  double x0 = p[0].x, y0 = p[0].y, x1 = x0, y1 = y0;
  for (const Particle& q : p)
    x0 = std::min(x0, q.x), y0 = std::min(y0, q.y), x1 = std::max(x1, q.x), y1 = std::max(y1, q.y);
  const auto nx = static_cast<std::size_t>((x1 - x0) / kReach) + 1,
             ny = static_cast<std::size_t>((y1 - y0) / kReach) + 1;
  const auto cell_of = [&](const Particle& q) {
    return static_cast<std::size_t>((q.y - y0) / kReach) * nx + static_cast<std::size_t>((q.x - x0) / kReach);
  };
  std::vector<std::uint32_t> start(nx * ny + 1, 0), member(p.size());
  for (const Particle& q : p) ++start[cell_of(q) + 1];
  for (std::size_t c = 0; c < nx * ny; ++c) start[c + 1] += start[c];
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < p.size(); ++k) member[fill[cell_of(p[k])]++] = static_cast<std::uint32_t>(k);
  }
  contacts.reserve(p.size() * 21 / 10);
  const auto test = [&](std::uint32_t a, std::uint32_t b) {
    const double dx = p[a].x - p[b].x, dy = p[a].y - p[b].y, reach = p[a].r + p[b].r;
    if (dx * dx + dy * dy < reach * reach) contacts.push_back({a, b, 0, 0});
  };
  // Each pair of cells once: the cell itself and its four "forward" neighbours.
  constexpr int kForward[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
  for (std::size_t cy = 0; cy < ny; ++cy)
    for (std::size_t cx = 0; cx < nx; ++cx) {
      const std::size_t c = cy * nx + cx;
      for (std::uint32_t s = start[c]; s < start[c + 1]; ++s) {
        for (std::uint32_t t = s + 1; t < start[c + 1]; ++t) test(member[s], member[t]);
        for (const auto& d : kForward) {
          const auto ox = static_cast<std::ptrdiff_t>(cx) + d[0], oy = static_cast<std::ptrdiff_t>(cy) + d[1];
          if (ox < 0 || ox >= static_cast<std::ptrdiff_t>(nx) || oy >= static_cast<std::ptrdiff_t>(ny)) continue;
          const std::size_t o = static_cast<std::size_t>(oy) * nx + static_cast<std::size_t>(ox);
          for (std::uint32_t t = start[o]; t < start[o + 1]; ++t) test(member[s], member[t]);
        }
      }
    }
  return contacts;
}

void assign_forces(std::vector<Contact>& contacts, const SyntheticOptions& opt, Rng& rng) {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    Contact& c = contacts[k];
    const double u = rng.uniform(), kind = rng.uniform();
    if (opt.force_levels > 0)
      c.fn = 2 * std::ceil(u * opt.force_levels) / opt.force_levels;
    else
      c.fn = -std::log1p(-u);  // exponential, mean 1
    if (kind < opt.tie_fraction && k > 0)
      c.fn = contacts[rng.below(k)].fn;  // an exact tie
    else if (kind > 0.999)
      c.fn = 0;  // touching, no force: not an edge
    else if (kind > 0.996)
      c.fn = -0.05 * u;  // a damped contact, slightly tensile
    const double t = rng.uniform();
    if (t < 0.05)
      c.ft = 0;  // no tangential load: not an edge
    else if (t < 0.13)
      c.ft = 0.5 * std::fabs(c.fn);  // sliding at the Coulomb cap (mu = 0.5)
    else
      c.ft = 0.5 * std::fabs(c.fn) * rng.uniform();
  }
}

}  // namespace

Frame synthetic_frame(const SyntheticOptions& options) {
  Rng rng(options.seed);
  Frame frame;
  frame.label = "synthetic N=" + std::to_string(options.particles) + " seed=" + std::to_string(options.seed);
  frame.particle_count = options.particles;
  frame.particles = place_particles(options, rng);
  frame.contacts = find_contacts(frame.particles);
  assign_forces(frame.contacts, options, rng);
  return frame;
}

}  // namespace fnet::testing
