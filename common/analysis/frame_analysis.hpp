// What fnet computes for every frame of a run: the diagrams of both force networks, and the
// twelve distances to the previous frame (bottleneck, W1, W2) x (PD0, PD1) x (normal, tangential).
#pragma once

#include <array>
#include <cstddef>

#include "common/analysis/stored_series.hpp"
#include "common/distance/distance_metric.hpp"
#include "common/distance/distance_result.hpp"
#include "common/distance/essential_convention.hpp"
#include "common/topology/force_network.hpp"
#include "common/topology/frame.hpp"
#include "common/topology/persistence.hpp"

namespace fnet {

struct FrameDiagramSet {
  FrameDiagrams normal, tangential;
  const FrameDiagrams& operator[](ForceKind kind) const { return kind == ForceKind::normal ? normal : tangential; }
};

// The frame must have passed validate(). threads > 1: the two networks at once.
FrameDiagramSet analyze_frame(const Frame& frame, int threads = 1);

const Diagram& diagram_of(const FrameDiagramSet& set, ForceKind force, int dim);

// The distance one of the stored metrics names.
DistanceMetric distance_metric(Metric metric);

// Distance between two diagrams. delta: the accepted relative error (0: exact).
DistanceResult diagram_distance(const Diagram& a, const Diagram& b, Metric metric,
                                EssentialConvention essential = EssentialConvention::floor);
DistanceResult diagram_distance(const Diagram& a, const Diagram& b, DistanceMetric metric,
                                EssentialConvention essential = EssentialConvention::floor, double delta = 0);

// The twelve distances between consecutive frames (exact unless a relative error is accepted),
// indexed by step_index().
struct StepDistances {
  std::array<double, kStoredSeries.size()> value{};
  std::array<double, kStoredSeries.size()> seconds{};  // CPU time of the thread that computed each
  double operator()(Metric metric, int dim, ForceKind force) const { return value[index(metric, dim, force)]; }
  static constexpr std::size_t index(Metric metric, int dim, ForceKind force) {
    return stored_series_index(metric, dim, force);
  }
};

// threads > 1: the distances shared among that many threads, the costliest first (Wasserstein
// before bottleneck, larger diagrams first); every value is the same as on one thread, bit for bit.
// delta > 0: each distance within that relative error (diagram_distance), the value an upper bound.
StepDistances step_distances(const FrameDiagramSet& previous, const FrameDiagramSet& current,
                             EssentialConvention essential = EssentialConvention::floor, int threads = 1,
                             double delta = 0);

}  // namespace fnet
