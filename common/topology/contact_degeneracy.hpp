// How many contacts per grain a frame's contact graph holds, in the one sense physics bounds for
// any size distribution: its degeneracy, the least K such that the grains can be taken one at a
// time, each touching at most K of the grains not yet taken.
//
// Grains that do not overlap, taken from the smallest to the largest, each touch at most as many
// grains not yet taken as fit around one grain at least their own size: the kissing number, 6
// for disks and 12 for spheres. So K <= 12 (in 2D K <= 5, since disks that touch make a planar
// graph), whatever the ratio of sizes: a large grain touching many small ones is taken after
// them. A frame with a large K holds contacts between grains that cannot all touch (a dense clique),
// and its triangles (at most grains x K(K-1)/2) are what the analysis spends its time on.
#pragma once

#include <cstddef>

#include "common/topology/frame.hpp"

namespace fnet {

// The degeneracy of the frame's contact graph (every contact counts, whatever its force). The
// frame must be valid (validate()): indices in range, no self-contact, no pair twice. O(grains +
// contacts) time and memory.
std::size_t contact_degeneracy(const Frame& frame);

}  // namespace fnet
