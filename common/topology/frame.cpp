#include "common/topology/frame.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <sstream>
#include <utility>

#include "common/topology/radix_sort.hpp"

namespace fnet {
namespace {

[[noreturn]] void reject(const Frame& frame, const std::string& what) {
  throw FrameError(frame.label.empty() ? what : frame.label + ": " + what);
}

std::string describe(const Contact& c, std::size_t row) {
  std::ostringstream s;
  s.precision(17);
  s << "contact " << row << " (i=" << c.i << ", j=" << c.j << ", fn=" << c.fn << ", ft=" << c.ft << ")";
  return s.str();
}

}  // namespace

std::size_t implied_particle_count(const std::vector<Contact>& contacts) {
  std::int64_t largest = -1;
  for (const Contact& c : contacts) largest = std::max({largest, c.i, c.j});
  return largest < 0 ? 0 : static_cast<std::size_t>(largest) + 1;  // unsigned: no overflow at INT64_MAX
}

void validate(const Frame& frame) {
  if (frame.dimension != 2 && frame.dimension != 3)
    reject(frame, "dimension " + std::to_string(frame.dimension) + " is neither 2 nor 3");
  if (frame.particle_count > std::size_t{UINT32_MAX}) {
    // Without a particle table the count came from a contact: name it.
    for (std::size_t k = 0; k < frame.contacts.size(); ++k) {
      const Contact& c = frame.contacts[k];
      if (std::max(c.i, c.j) >= std::int64_t{UINT32_MAX})
        reject(frame, describe(c, k) + ": particle index exceeds the largest supported, 2^32 - 2");
    }
    reject(frame, "particle count " + std::to_string(frame.particle_count) + " exceeds 2^32 - 1");
  }
  if (const std::size_t declarable = kDeclaredParticlesPerContact * frame.contacts.size() + kDeclaredParticlesFloor;
      frame.particles.empty() && frame.particle_count > declarable) {
    const std::string bound = "more than " + std::to_string(declarable) + " particles (" +
                              std::to_string(kDeclaredParticlesPerContact) + " per contact + " +
                              std::to_string(kDeclaredParticlesFloor) +
                              ") without a particle table, which must list the grains";
    // Without a particle table the count is usually implied by the largest index: name its contact.
    for (std::size_t k = 0; k < frame.contacts.size(); ++k) {
      const Contact& c = frame.contacts[k];
      if (std::max(c.i, c.j) >= static_cast<std::int64_t>(declarable))
        reject(frame, describe(c, k) + ": particle index implies " + bound);
    }
    reject(frame, "particle count " + std::to_string(frame.particle_count) + ": " + bound);
  }
  if (!frame.particles.empty() && frame.particles.size() != frame.particle_count)
    reject(frame, "particle table has " + std::to_string(frame.particles.size()) + " rows but the frame declares " +
                      std::to_string(frame.particle_count) + " particles");

  for (std::size_t k = 0; k < frame.particles.size(); ++k) {
    const Particle& p = frame.particles[k];
    const auto where = [&] {
      std::ostringstream s;
      s.precision(17);
      s << "particle " << k << " (x=" << p.x << ", y=" << p.y;
      if (frame.dimension == 3 || p.z != 0) s << ", z=" << p.z;
      s << ", r=" << p.r << ")";
      return s.str();
    };
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.r))
      reject(frame, where() + ": non-finite value");
    if (p.r < 0) reject(frame, where() + ": negative radius");
    if (frame.dimension == 2 && p.z != 0) reject(frame, where() + ": z is not 0 in a 2D frame");
  }

  const auto n = static_cast<std::int64_t>(frame.particle_count);
  // Pairs keyed lo * n + hi sort as (lo, hi) do; by (key, row), the radix sort build_network uses.
  std::vector<KeyedRecord> pairs(frame.contacts.size()), scratch(frame.contacts.size());
  std::uint64_t least = ~std::uint64_t{0}, greatest = 0;
  for (std::size_t k = 0; k < frame.contacts.size(); ++k) {
    const Contact& c = frame.contacts[k];
    if (!std::isfinite(c.fn) || !std::isfinite(c.ft)) reject(frame, describe(c, k) + ": non-finite force");
    if (c.i < 0 || c.j < 0 || c.i >= n || c.j >= n)
      reject(frame, describe(c, k) + ": particle index out of range [0, " + std::to_string(n) + ")");
    if (c.i == c.j) reject(frame, describe(c, k) + ": self-contact");
    const auto lo = static_cast<std::uint64_t>(std::min(c.i, c.j));
    const auto hi = static_cast<std::uint64_t>(std::max(c.i, c.j));
    pairs[k] = {lo * static_cast<std::uint64_t>(n) + hi, k};
    least = std::min(least, pairs[k].key), greatest = std::max(greatest, pairs[k].key);
  }
  if (pairs.empty()) return;
  const std::span<const KeyedRecord> sorted = sort_keyed(pairs, scratch, least, greatest);
  for (std::size_t k = 1; k < sorted.size(); ++k) {
    if (sorted[k].key != sorted[k - 1].key) continue;
    const std::size_t first = std::min(sorted[k - 1].tie, sorted[k].tie);
    const std::size_t second = std::max(sorted[k - 1].tie, sorted[k].tie);
    reject(frame, describe(frame.contacts[second], second) + ": duplicate of contact " + std::to_string(first) +
                      " (same pair of particles)");
  }
}

}  // namespace fnet
