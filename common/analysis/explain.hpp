// Where two frames differ most: the largest terms of the optimal matching behind a distance
// between their diagrams, each point with the grains and contacts that create and destroy it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/distance/distance_metric.hpp"
#include "common/distance/distance_result.hpp"
#include "common/distance/essential_convention.hpp"
#include "common/topology/diagram.hpp"
#include "common/topology/force_network.hpp"
#include "common/topology/frame.hpp"

namespace fnet {

// A simplex as grains: one grain (a vertex), two (an edge: a contact) or three (a triangle).
struct ExplainedSimplex {
  std::vector<std::uint32_t> grains;             // particle indices of the frame, ascending
  std::vector<std::array<double, 3>> positions;  // (x, y, z) of each grain; empty for a frame without particles
  int dimension = 2;                             // the frame's: z is 0 in 2D, and not written
  bool operator==(const ExplainedSimplex&) const = default;
};

struct ExplainedPoint {
  PersistencePoint point;
  ExplainedSimplex birth_simplex;                 // PD0 a grain, PD1 the contact closing the loop
  std::optional<ExplainedSimplex> death_simplex;  // PD0 the merging contact, PD1 the filling triangle
};

// One term of the matching: a point of frame a with one of frame b, or either with the diagonal.
struct ExplainedTerm {
  std::size_t rank = 0;                // 1 for the longest
  double cost = 0;                     // the term's L-infinity length under the convention
  std::optional<ExplainedPoint> a, b;  // none: matched to the diagonal
};

struct Explanation {
  DistanceResult distance;
  // The k longest terms of positive length, longest first; for the bottleneck the first is the
  // one that attains d_B. None when the distance is 0 or infinite.
  std::vector<ExplainedTerm> terms;
};

struct ExplainRequest {
  DistanceMetric metric;
  int dim = 1;  // 0 or 1
  ForceKind force = ForceKind::normal;
  EssentialConvention essential = EssentialConvention::floor;
  std::size_t k = 1;  // >= 1
};

// Validates both frames (FrameError) and the request (std::invalid_argument), then computes both
// networks' diagrams with their pairs and the distance with its matching.
Explanation explain(const Frame& a, const Frame& b, const ExplainRequest& request);

}  // namespace fnet
