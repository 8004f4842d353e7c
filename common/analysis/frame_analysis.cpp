#include "common/analysis/frame_analysis.hpp"

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

DistanceResult diagram_distance(const Diagram& a, const Diagram& b, Metric metric, EssentialConvention essential) {
  switch (metric) {
    case Metric::bottleneck:
      return diagram_distance_q(a, b, 0, essential);
    case Metric::wasserstein1:
      return diagram_distance_q(a, b, 1, essential);
    case Metric::wasserstein2:
      return diagram_distance_q(a, b, 2, essential);
  }
  return {};
}

DistanceResult diagram_distance_q(const Diagram& a, const Diagram& b, double q, EssentialConvention essential,
                                  double delta) {
  if (q == 0) return bottleneck_distance(a, b, {essential, delta});
  return wasserstein_distance(a, b, {.q = q, .essential = essential, .delta = delta});
}

StepDistances step_distances(const FrameDiagramSet& previous, const FrameDiagramSet& current,
                             EssentialConvention essential) {
  StepDistances out;
  for (const ForceKind force : kForces)
    for (int dim = 0; dim < 2; ++dim)
      for (const Metric metric : kMetrics)
        out.value[StepDistances::index(metric, dim, force)] =
            diagram_distance(diagram_of(previous, force, dim), diagram_of(current, force, dim), metric, essential)
                .value;
  return out;
}

}  // namespace fnet
