#include "tests/support/synthetic_frame.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
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
constexpr double kReach = 2 * kMaxRadius;
constexpr double kSpacing3d = 0.99;  // tuned with kJitter3d for mean degree ~6
constexpr double kJitter3d = 0.05;

// Disks on a jittered triangular lattice, a few squeezed into the centre of a lattice triangle.
std::vector<Particle> lattice_2d(const SyntheticOptions& opt, Rng& rng) {
  const std::size_t n = opt.particles;
  const auto interstitials =
      std::min(n / 4, static_cast<std::size_t>(std::llround(opt.interstitial_fraction * static_cast<double>(n))));
  const std::size_t sites = n - interstitials;
  const auto cols = std::max<std::size_t>(
      2, static_cast<std::size_t>(std::llround(std::sqrt(static_cast<double>(sites) * 2 / std::sqrt(3.0)))));
  const double spacing = opt.spacing > 0 ? opt.spacing : kSpacing, jitter = opt.jitter > 0 ? opt.jitter : kJitter;
  const double row_height = spacing * std::sqrt(3.0) / 2;

  std::vector<Particle> at(n);
  for (std::size_t k = 0; k < sites; ++k) {
    const std::size_t r = k / cols, c = k % cols;
    at[k].x = (static_cast<double>(c) + 0.5 * static_cast<double>(r % 2)) * spacing + jitter * (2 * rng.uniform() - 1);
    at[k].y = static_cast<double>(r) * row_height + jitter * (2 * rng.uniform() - 1);
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
  return at;
}

// Spheres on a jittered face-centred cubic lattice, built as triangular layers stacked ABC
// (nearest neighbours kSpacing3d apart: twelve of them, about half touching).
std::vector<Particle> lattice_3d(const SyntheticOptions& opt, Rng& rng) {
  const std::size_t n = opt.particles;
  const double spacing = opt.spacing > 0 ? opt.spacing : kSpacing3d, jitter = opt.jitter > 0 ? opt.jitter : kJitter3d;
  const auto side = std::max<std::size_t>(2, static_cast<std::size_t>(std::ceil(std::cbrt(static_cast<double>(n)))));
  const double row_height = spacing * std::sqrt(3.0) / 2, layer_height = spacing * std::sqrt(2.0 / 3.0);
  std::vector<Particle> at(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t layer = k / (side * side), r = k / side % side, c = k % side;
    const double shift = static_cast<double>(layer % 3);  // A, B, C: offset by a third of a triangle
    at[k].x = (static_cast<double>(c) + 0.5 * static_cast<double>(r % 2) + 0.5 * shift) * spacing +
              jitter * (2 * rng.uniform() - 1);
    at[k].y = (static_cast<double>(r) + shift / 3) * row_height + jitter * (2 * rng.uniform() - 1);
    at[k].z = static_cast<double>(layer) * layer_height + jitter * (2 * rng.uniform() - 1);
  }
  return at;
}

// Radii, then ids unrelated to position, as in a simulator after the grains have mixed.
std::vector<Particle> shuffled_grains(std::vector<Particle> at, Rng& rng) {
  const std::size_t n = at.size();
  for (Particle& p : at) p.r = kMinRadius + (kMaxRadius - kMinRadius) * rng.uniform();
  std::vector<std::uint32_t> id(n);
  for (std::size_t k = 0; k < n; ++k) id[k] = static_cast<std::uint32_t>(k);
  for (std::size_t k = n; k > 1; --k) std::swap(id[k - 1], id[rng.below(k)]);
  std::vector<Particle> particles(n);
  for (std::size_t k = 0; k < n; ++k) particles[id[k]] = at[k];
  return particles;
}

// Overlapping pairs by grid hashing with cells as wide as the longest possible contact. A 2D
// frame (every z 0) is one layer of cells.
std::vector<Contact> find_contacts(const std::vector<Particle>& p) {
  std::vector<Contact> contacts;
  if (p.empty()) return contacts;
  double x0 = p[0].x, y0 = p[0].y, z0 = p[0].z, x1 = x0, y1 = y0, z1 = z0;
  for (const Particle& q : p) {
    x0 = std::min(x0, q.x), y0 = std::min(y0, q.y), z0 = std::min(z0, q.z);
    x1 = std::max(x1, q.x), y1 = std::max(y1, q.y), z1 = std::max(z1, q.z);
  }
  const auto nx = static_cast<std::size_t>((x1 - x0) / kReach) + 1,
             ny = static_cast<std::size_t>((y1 - y0) / kReach) + 1,
             nz = static_cast<std::size_t>((z1 - z0) / kReach) + 1;
  const auto cell_of = [&](const Particle& q) {
    return (static_cast<std::size_t>((q.z - z0) / kReach) * ny + static_cast<std::size_t>((q.y - y0) / kReach)) * nx +
           static_cast<std::size_t>((q.x - x0) / kReach);
  };
  const std::size_t cells = nx * ny * nz;
  std::vector<std::uint32_t> start(cells + 1, 0), member(p.size());
  for (const Particle& q : p) ++start[cell_of(q) + 1];
  for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < p.size(); ++k) member[fill[cell_of(p[k])]++] = static_cast<std::uint32_t>(k);
  }
  contacts.reserve(p.size() * (nz > 1 ? 32 : 21) / 10);
  const auto test = [&](std::uint32_t a, std::uint32_t b) {
    const double dx = p[a].x - p[b].x, dy = p[a].y - p[b].y, dz = p[a].z - p[b].z, reach = p[a].r + p[b].r;
    if (dx * dx + dy * dy + dz * dz < reach * reach) contacts.push_back({a, b, 0, 0});
  };
  // Each pair of cells once: the cell itself and its 13 "forward" neighbours (the first four in
  // its own layer).
  constexpr int kForward[13][3] = {{1, 0, 0},  {-1, 1, 0}, {0, 1, 0}, {1, 1, 0},  {-1, -1, 1}, {0, -1, 1}, {1, -1, 1},
                                   {-1, 0, 1}, {0, 0, 1},  {1, 0, 1}, {-1, 1, 1}, {0, 1, 1},   {1, 1, 1}};
  const auto inside = [](std::size_t c, int d, std::size_t n) {
    const auto o = static_cast<std::ptrdiff_t>(c) + d;
    return o >= 0 && o < static_cast<std::ptrdiff_t>(n);
  };
  for (std::size_t cz = 0; cz < nz; ++cz)
    for (std::size_t cy = 0; cy < ny; ++cy)
      for (std::size_t cx = 0; cx < nx; ++cx) {
        const std::size_t c = (cz * ny + cy) * nx + cx;
        for (std::uint32_t s = start[c]; s < start[c + 1]; ++s) {
          for (std::uint32_t t = s + 1; t < start[c + 1]; ++t) test(member[s], member[t]);
          for (const auto& d : kForward) {
            if (!inside(cx, d[0], nx) || !inside(cy, d[1], ny) || !inside(cz, d[2], nz)) continue;
            const auto step = (static_cast<std::ptrdiff_t>(d[2] * static_cast<std::ptrdiff_t>(ny)) + d[1]) *
                                  static_cast<std::ptrdiff_t>(nx) +
                              d[0];
            const std::size_t o = c + static_cast<std::size_t>(step);
            for (std::uint32_t t = start[o]; t < start[o + 1]; ++t) test(member[s], member[t]);
          }
        }
      }
  return contacts;
}

// Ties, exact zeros and slightly tensile contacts, as real data have them; u is the uniform
// draw behind c.fn (a tensile force is -0.05 u).
// Every overlapping pair pushed apart along its line of centres by half its overlap, all at once.
void relax(std::vector<Particle>& p, int rounds) {
  std::vector<Particle> push(p.size());
  for (int round = 0; round < rounds; ++round) {
    std::fill(push.begin(), push.end(), Particle{});
    for (const Contact& c : find_contacts(p)) {
      const auto i = static_cast<std::size_t>(c.i), j = static_cast<std::size_t>(c.j);
      const double dx = p[i].x - p[j].x, dy = p[i].y - p[j].y, dz = p[i].z - p[j].z;
      const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (d == 0) continue;
      const double s = 0.25 * (p[i].r + p[j].r - d) / d;
      push[i].x += s * dx, push[i].y += s * dy, push[i].z += s * dz;
      push[j].x -= s * dx, push[j].y -= s * dy, push[j].z -= s * dz;
    }
    for (std::size_t k = 0; k < p.size(); ++k) p[k].x += push[k].x, p[k].y += push[k].y, p[k].z += push[k].z;
  }
}

void mark_special(std::vector<Contact>& contacts, std::size_t k, double u, double tie_fraction, Rng& rng) {
  Contact& c = contacts[k];
  const double kind = rng.uniform();
  if (kind < tie_fraction && k > 0)
    c.fn = contacts[rng.below(k)].fn;  // an exact tie
  else if (kind > 0.999)
    c.fn = 0;  // touching, no force: not an edge
  else if (kind > 0.996)
    c.fn = -0.05 * u;  // a damped contact, slightly tensile
}

// |ft| <= 0.5 |fn| (mu = 0.5): some contacts unloaded, some sliding at the cap, the rest below.
double tangential(double fn, Rng& rng) {
  const double t = rng.uniform();
  if (t < 0.05) return 0;                    // no tangential load: not an edge
  if (t < 0.13) return 0.5 * std::fabs(fn);  // sliding at the Coulomb cap (mu = 0.5)
  return 0.5 * std::fabs(fn) * rng.uniform();
}

void assign_forces(std::vector<Contact>& contacts, const SyntheticOptions& opt, Rng& rng) {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    Contact& c = contacts[k];
    const double u = rng.uniform();
    if (opt.force_levels > 0)
      c.fn = 2 * std::ceil(u * opt.force_levels) / opt.force_levels;
    else
      c.fn = -std::log1p(-u);  // exponential, mean 1
    mark_special(contacts, k, u, opt.tie_fraction, rng);
    c.ft = tangential(c.fn, rng);
  }
}

std::uint64_t pair_key(std::int64_t i, std::int64_t j) {
  const auto a = static_cast<std::uint64_t>(std::min(i, j)), b = static_cast<std::uint64_t>(std::max(i, j));
  return a << 32 | b;
}

}  // namespace

Frame synthetic_frame(const SyntheticOptions& options) {
  Rng rng(options.seed);
  Frame frame;
  frame.label = "synthetic " + std::string(options.dimension == 3 ? "3D " : "") +
                "N=" + std::to_string(options.particles) + " seed=" + std::to_string(options.seed);
  frame.particle_count = options.particles;
  frame.dimension = options.dimension;
  frame.particles = shuffled_grains(options.dimension == 3 ? lattice_3d(options, rng) : lattice_2d(options, rng), rng);
  relax(frame.particles, options.relax_rounds);
  frame.contacts = find_contacts(frame.particles);
  assign_forces(frame.contacts, options, rng);
  return frame;
}

}  // namespace fnet::testing

namespace fnet::testing {

SyntheticOptions disordered_packing(int dimension, std::size_t particles, std::uint64_t seed) {
  return {.particles = particles,
          .seed = seed,
          .dimension = dimension,
          .spacing = dimension == 3 ? 1.02 : 1.0,
          .jitter = 0.5,
          .relax_rounds = 30};
}

Frame next_frame(const Frame& previous, const NextFrameOptions& options) {
  Rng rng(options.seed ^ 0x5DEECE66Dull);
  Frame frame;
  frame.label = previous.label + " next seed=" + std::to_string(options.seed);
  frame.dimension = previous.dimension;
  frame.particle_count = previous.particle_count;
  frame.particles = previous.particles;
  const double shrink = 1 - options.strain, move = options.displacement;
  for (Particle& p : frame.particles) {
    p.x = p.x * shrink + move * (2 * rng.uniform() - 1);
    p.y = p.y * shrink + move * (2 * rng.uniform() - 1);
    if (frame.dimension == 3) p.z = p.z * shrink + move * (2 * rng.uniform() - 1);
  }
  std::unordered_map<std::uint64_t, const Contact*> before;
  before.reserve(previous.contacts.size());
  for (const Contact& c : previous.contacts) before.emplace(pair_key(c.i, c.j), &c);
  frame.contacts = find_contacts(frame.particles);
  for (std::size_t k = 0; k < frame.contacts.size(); ++k) {
    Contact& c = frame.contacts[k];
    const double u = rng.uniform(), v = rng.uniform();
    const auto it = before.find(pair_key(c.i, c.j));
    const bool persists = it != before.end() && it->second->fn > 0;
    c.fn =
        persists ? it->second->fn * (1 + options.force_change * (2 * u - 1)) : -options.new_force_mean * std::log1p(-u);
    mark_special(frame.contacts, k, u, options.tie_fraction, rng);
    c.ft = persists ? std::min(0.5 * std::fabs(c.fn), it->second->ft * (1 + options.force_change * (2 * v - 1)))
                    : tangential(c.fn, rng);
  }
  return frame;
}

}  // namespace fnet::testing
