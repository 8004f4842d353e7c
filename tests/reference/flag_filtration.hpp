// The superlevel filtration of a frame's flag complex (2-skeleton), built from the frame alone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/topology/force_network.hpp"
#include "common/topology/frame.hpp"

namespace fnet::reference {

struct Simplex {
  std::vector<std::uint32_t> vertices;  // ascending; 1, 2 or 3 of them
  double value = 0;                     // f(simplex), normalized by the mean force
  std::size_t dimension() const { return vertices.size() - 1; }
};

struct Filtration {
  std::vector<Simplex> simplices;  // a valid superlevel order: value descending, faces first on ties
  double mean_force = 0;           // mean |force| over contacts with |force| > 0; 0 if none
  std::size_t vertices = 0, edges = 0, triangles = 0;
};

// Mean |force| over the contacts with |force| > 0 (0 if none), summed smallest first in extended
// precision so that it does not depend on the order of the rows.
double mean_force(const Frame& frame, ForceKind kind);

// Vertices: every particle, f = max incident edge or 0. Edges: contacts with |force| > 0,
// f = |force| / mean. Triangles: every 3-clique of edges, f = min of its edges.
// Throws FrameError (via fnet::validate) for a frame that is not valid.
Filtration flag_filtration(const Frame& frame, ForceKind kind);

// The same with a given normalizing mean (> 0 unless there are no edges): lets a comparison
// isolate the persistence from the last bit of the mean, whose rounding depends on summation order.
Filtration flag_filtration(const Frame& frame, ForceKind kind, double mean);

}  // namespace fnet::reference
