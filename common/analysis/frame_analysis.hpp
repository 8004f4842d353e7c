// What fnet computes for every frame of a run: the diagrams of both force networks, and the
// twelve distances to the previous frame (bottleneck, W1, W2) x (PD0, PD1) x (normal, tangential).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "common/distance/distance_metric.hpp"
#include "common/distance/distance_result.hpp"
#include "common/distance/essential_convention.hpp"
#include "common/topology/force_network.hpp"
#include "common/topology/frame.hpp"
#include "common/topology/persistence.hpp"

namespace fnet {

enum class Metric { bottleneck, wasserstein1, wasserstein2 };
inline constexpr std::array<Metric, 3> kMetrics{Metric::bottleneck, Metric::wasserstein1, Metric::wasserstein2};
inline constexpr std::array<ForceKind, 2> kForces{ForceKind::normal, ForceKind::tangential};

std::string_view to_string(Metric metric);

struct FrameDiagramSet {
  FrameDiagrams normal, tangential;
  const FrameDiagrams& operator[](ForceKind kind) const { return kind == ForceKind::normal ? normal : tangential; }
};

// The frame must have passed validate().
FrameDiagramSet analyze_frame(const Frame& frame);

const Diagram& diagram_of(const FrameDiagramSet& set, ForceKind force, int dim);

// The distance one of the stored metrics names.
DistanceMetric distance_metric(Metric metric);

// Distance between two diagrams. delta: the accepted relative error (0: exact).
DistanceResult diagram_distance(const Diagram& a, const Diagram& b, Metric metric,
                                EssentialConvention essential = EssentialConvention::floor);
DistanceResult diagram_distance(const Diagram& a, const Diagram& b, DistanceMetric metric,
                                EssentialConvention essential = EssentialConvention::floor, double delta = 0);

// The twelve exact distances between consecutive frames, indexed by step_index().
struct StepDistances {
  std::array<double, 12> value{};
  double operator()(Metric metric, int dim, ForceKind force) const { return value[index(metric, dim, force)]; }
  static std::size_t index(Metric metric, int dim, ForceKind force) {
    return static_cast<std::size_t>(metric) * 4 + static_cast<std::size_t>(dim) * 2 +
           (force == ForceKind::normal ? 0 : 1);
  }
};

StepDistances step_distances(const FrameDiagramSet& previous, const FrameDiagramSet& current,
                             EssentialConvention essential = EssentialConvention::floor);

}  // namespace fnet
