// PD0 and PD1 of the superlevel filtration of a force network's flag complex (2-skeleton).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/topology/diagram.hpp"
#include "common/topology/force_network.hpp"

namespace fnet {

struct FrameDiagrams {
  Diagram pd0, pd1;  // canonical order, zero-length points dropped
  std::size_t vertices = 0;
  std::size_t edges = 0;
  std::size_t triangles = 0;
};

// f(vertex) = max incident edge (0 if none), f(triangle) = min of its edges; simplices enter in
// decreasing f. PD0 by union-find with the elder rule; PD1 by reducing the triangle boundary
// matrix, exact for any graph (planar or not). The result does not depend on how ties are broken.
FrameDiagrams compute_persistence(const ForceNetwork& network);

// A simplex of the flag complex by its vertices (the network's vertex indices, ascending): a
// vertex (a grain), an edge (a contact) or a triangle; size 0 is no simplex at all.
struct Simplex {
  std::array<std::uint32_t, 3> vertices{};
  std::uint8_t size = 0;
  bool operator==(const Simplex&) const = default;
};

// The pair of simplices behind one diagram point: the one whose entry creates the class and the
// one whose entry destroys it; f(birth) == point.birth and f(death) == point.death exactly.
//   PD0: birth a vertex (the lower-indexed end of the strongest contact of the component's
//        elder grain pair), death the edge that merges it into an elder component; none for a
//        class that never dies (a rattler's birth is the rattler itself).
//   PD1: birth the edge that closes the loop, death the triangle that fills it; none for a loop
//        that never dies.
struct PointSimplices {
  Simplex birth, death;
  bool operator==(const PointSimplices&) const = default;
};

// The diagrams and, point for point (same index, same canonical order), their simplices.
struct PairedDiagrams {
  FrameDiagrams diagrams;
  std::vector<PointSimplices> pd0, pd1;
};

// The same diagrams as compute_persistence, with the simplices that pair each point. Ties
// among values are broken as the sweep meets them (vertices by index within an edge, edges in
// the network's order), so where f has ties the pairing is one of the valid ones. A separate
// entry point so that the per-frame analysis, which needs the diagrams only, pays nothing for it.
PairedDiagrams compute_persistence_pairs(const ForceNetwork& network);

}  // namespace fnet
