// Synthetic 2D contact networks that look like a dense granular packing, at any size, in O(N).
#pragma once

#include <cstddef>
#include <cstdint>

#include "common/topology/frame.hpp"

namespace fnet::testing {

struct SyntheticOptions {
  std::size_t particles = 2000;
  std::uint64_t seed = 1;
  // Share of particles squeezed into the centre of a lattice triangle: each makes a K4 (a 2-sphere
  // in the flag complex), the non-planar bits that exercise the exact PD1 reduction.
  double interstitial_fraction = 0.002;
  // Share of contacts whose normal force copies another contact's exactly (ties are normal in
  // real data: lattices, symmetric loads, sliding contacts at the Coulomb cap).
  double tie_fraction = 0.005;
  // > 0 quantizes the normal force to this many levels: a frame made almost only of ties.
  int force_levels = 0;
};

// Disks with diameters uniform in [0.8, 1.2] on a jittered triangular lattice (spacing 0.935,
// jitter ~0.05), contacts where disks overlap: mean degree ~4.2, ~0.9 N triangles, ~1% rattlers.
// Normal forces are exponential (mean 1), a few slightly tensile or exactly zero; tangential
// forces are |ft| <= 0.5 |fn|, with sliding contacts exactly at the cap and some exact zeros.
// Particle ids are a random permutation of the positions, as in a simulator after mixing.
// Deterministic for a given seed on every platform (own RNG, no <random> distributions).
Frame synthetic_frame(const SyntheticOptions& options);

}  // namespace fnet::testing
