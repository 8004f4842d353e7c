#include "common/analysis/frame_analysis.hpp"

#include <stdexcept>

#include "common/distance/bottleneck.hpp"
#include "common/distance/wasserstein.hpp"

namespace fnet {

std::string_view to_string(Metric metric) {
  switch (metric) {
    case Metric::bottleneck:
      return "bottleneck";
    case Metric::wasserstein1:
      return "wasserstein1";
    case Metric::wasserstein2:
      return "wasserstein2";
  }
  return "?";
}

FrameDiagramSet analyze_frame(const Frame& frame) {
  return {compute_persistence(build_network(frame, ForceKind::normal)),
          compute_persistence(build_network(frame, ForceKind::tangential))};
}

const Diagram& diagram_of(const FrameDiagramSet& set, ForceKind force, int dim) {
  const FrameDiagrams& d = set[force];
  return dim == 0 ? d.pd0 : d.pd1;
}

DistanceMetric distance_metric(Metric metric) {
  switch (metric) {
    case Metric::bottleneck:
      return DistanceMetric::bottleneck();
    case Metric::wasserstein1:
      return DistanceMetric::wasserstein(1);
    case Metric::wasserstein2:
      return DistanceMetric::wasserstein(2);
  }
  throw std::invalid_argument("unknown stored metric");
}

DistanceResult diagram_distance(const Diagram& a, const Diagram& b, Metric metric, EssentialConvention essential) {
  return diagram_distance(a, b, distance_metric(metric), essential);
}

DistanceResult diagram_distance(const Diagram& a, const Diagram& b, DistanceMetric metric,
                                EssentialConvention essential, double delta) {
  if (metric.is_bottleneck()) return bottleneck_distance(a, b, {.essential = essential, .relative_error = delta});
  return wasserstein_distance(a, b, {.q = metric.q, .essential = essential, .delta = delta});
}

StepDistances step_distances(const FrameDiagramSet& previous, const FrameDiagramSet& current,
                             EssentialConvention essential) {
  StepDistances out;
  for (std::size_t k = 0; k < kStoredSeries.size(); ++k) {
    const StoredSeries& s = kStoredSeries[k];
    out.value[k] =
        diagram_distance(diagram_of(previous, s.force, s.dim), diagram_of(current, s.force, s.dim), s.metric, essential)
            .value;
  }
  return out;
}

}  // namespace fnet
