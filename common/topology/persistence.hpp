// PD0 and PD1 of the superlevel filtration of a force network's flag complex (2-skeleton).
#pragma once

#include <cstddef>

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

}  // namespace fnet
