// Synthetic 2D and 3D contact networks that look like a dense granular packing, at any size, in
// O(N), and the frame that follows one in a slow compression.
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
  // 2: disks in the plane; 3: spheres (interstitial_fraction is not used).
  int dimension = 2;
  // Lattice spacing and half-width of the uniform jitter; 0: the defaults below.
  double spacing = 0, jitter = 0;
  // > 0: that many rounds pushing overlapping grains apart (each pair by half its overlap, all
  // pairs at once) after the jitter: a disordered packing instead of a lattice.
  int relax_rounds = 0;
};

// Disks with diameters uniform in [0.8, 1.2] on a jittered triangular lattice (spacing 0.935,
// jitter ~0.05), contacts where disks overlap: mean degree ~4.2, ~0.9 N triangles, ~1% rattlers.
// Normal forces are exponential (mean 1), a few slightly tensile or exactly zero; tangential
// forces are |ft| <= 0.5 |fn|, with sliding contacts exactly at the cap and some exact zeros.
// Particle ids are a random permutation of the positions, as in a simulator after mixing.
// Deterministic for a given seed on every platform (own RNG, no <random> distributions).
// dimension 3: spheres with diameters uniform in [0.8, 1.2] on a jittered face-centred cubic
// lattice (spacing 0.99, jitter ~0.03), contacts where spheres overlap: mean degree ~6 as in a
// jammed 3D packing; forces, ties and zeros as in 2D.
Frame synthetic_frame(const SyntheticOptions& options);

// How the next frame of a slow compression differs from the last one.
struct NextFrameOptions {
  std::uint64_t seed = 1;
  double strain = 1e-3;         // every position scaled by 1 - strain (uniform compression)
  double displacement = 4e-3;   // plus a uniform non-affine move of up to this, per coordinate
  double force_change = 0.03;   // a persisting contact's forces scaled by 1 +- up to this
  double new_force_mean = 0.2;  // a contact that closes starts with an exponential force of this mean
  double tie_fraction = 0.005;  // as in SyntheticOptions
};

// Disordered packings whose networks look like a real one: the lattice jittered by half a
// spacing, then 30 relaxation rounds. 2D (spacing 1.0): mean degree 4.1, 0.54 N triangles, PD1 of
// ~0.6 N points, ~89 % of them never dying, as the LAMMPS frame at rho 0.90 of tests/data (4.16,
// 0.54 N, 0.63 N, 86 %). 3D (spacing 1.02): mean degree 5.9, 1.1 N triangles, PD1 ~1.1 N points,
// ~82 % never dying.
SyntheticOptions disordered_packing(int dimension, std::size_t particles, std::uint64_t seed);

// The frame after `previous`: grains moved (same radii, ids and dimension), contacts found again
// where they overlap, so that a small share opens and closes (on disordered_packing(): ~0.5 % each
// in 2D, ~1.2 % in 3D);
// persisting contacts keep their forces up to a few per cent, new ones start weak; ties, exact
// zeros and slightly tensile contacts as in synthetic_frame(). Deterministic for a given seed.
Frame next_frame(const Frame& previous, const NextFrameOptions& options);

}  // namespace fnet::testing
