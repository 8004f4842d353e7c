// A frame's force network: the contact graph weighted by normalized force.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "common/topology/frame.hpp"

namespace fnet {

enum class ForceKind { normal, tangential };

std::string_view to_string(ForceKind kind);
// Parses "normal" / "tangential"; throws std::invalid_argument naming the bad value.
ForceKind parse_force_kind(std::string_view text);

struct Edge {
  std::uint32_t u = 0, v = 0;  // u < v
  double value = 0;            // force / mean force, > 0
};

// Edges are the contacts whose force magnitude is > 0, normalized by the mean over exactly those
// contacts. They are kept in filtration order: value descending (ties in an order that does not
// depend on the order of the input rows).
struct ForceNetwork {
  std::size_t vertex_count = 0;
  std::vector<Edge> edges;
  double mean_force = 0;  // 0 when there are no edges
};

// Builds the network of one force kind. The frame must have passed validate().
ForceNetwork build_network(const Frame& frame, ForceKind kind);

}  // namespace fnet
