// A 3D packing small enough to count by hand: spheres on a jittered face-centred cubic lattice,
// each in contact with the neighbours it overlaps.
#pragma once

#include <cstdint>

#include "common/topology/frame.hpp"

namespace fnet::testing {

struct FccOptions {
  int cells = 3;          // cubic unit cells per side: 4·cells³ spheres
  double spacing = 0.98;  // nearest-neighbour distance on the lattice; < 2·radius: neighbours overlap
  double radius = 0.5;    // every sphere's
  double jitter = 0.004;  // each coordinate moved by up to ± this (keep it < (2·radius − spacing)/2)
  std::uint64_t seed = 1;
};

// A dimension-3 frame: sphere g = 4·((cz·cells + cy)·cells + cx) + b, b the basis site of unit cell
// (cx, cy, cz). Contacts (i < j, in i then j order) where two spheres overlap: fn = 1000 times the
// overlap rounded to 0.001 (a few tie), ft = fn times a factor in [0.1, 0.5] that varies with the
// pair.
// Deterministic for a given seed on every platform (own RNG).
Frame fcc_frame(const FccOptions& options);

}  // namespace fnet::testing
