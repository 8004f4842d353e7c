#include "common/analysis/frame_analysis.hpp"

#include <time.h>

#include <algorithm>
#include <atomic>
#include <future>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

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

namespace {

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

FrameDiagrams diagrams_of(const Frame& frame, ForceKind kind) {
  return compute_persistence(build_network(frame, kind));
}

// A guess at a distance's cost, to start the longest first: the Wasserstein solves dominate, and
// grow faster than linearly with the points.
double expected_cost(const StoredSeries& s, const FrameDiagramSet& previous, const FrameDiagramSet& current) {
  const double points =
      static_cast<double>(diagram_of(previous, s.force, s.dim).size() + diagram_of(current, s.force, s.dim).size());
  return s.metric == Metric::bottleneck ? points : 16 * points;
}

}  // namespace

FrameDiagramSet analyze_frame(const Frame& frame, int threads) {
  if (threads <= 1) return {diagrams_of(frame, ForceKind::normal), diagrams_of(frame, ForceKind::tangential)};
  std::future<FrameDiagrams> tangential =
      std::async(std::launch::async, diagrams_of, std::cref(frame), ForceKind::tangential);
  FrameDiagrams normal = diagrams_of(frame, ForceKind::normal);
  return {std::move(normal), tangential.get()};
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
                             EssentialConvention essential, int threads, double delta) {
  StepDistances out;
  const auto measure = [&](std::size_t k) {
    const StoredSeries& s = kStoredSeries[k];
    const double start = thread_cpu_seconds();
    out.value[k] = diagram_distance(diagram_of(previous, s.force, s.dim), diagram_of(current, s.force, s.dim),
                                    distance_metric(s.metric), essential, delta)
                       .value;
    out.seconds[k] = thread_cpu_seconds() - start;
  };
  if (threads <= 1) {
    for (std::size_t k = 0; k < kStoredSeries.size(); ++k) measure(k);
    return out;
  }
  std::array<std::size_t, kStoredSeries.size()> order{};
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return expected_cost(kStoredSeries[x], previous, current) > expected_cost(kStoredSeries[y], previous, current);
  });
  std::atomic<std::size_t> next{0};
  // Each worker takes the next distance in order until none is left; a distance's exception ends
  // its worker and is rethrown here.
  const auto work = [&] {
    for (std::size_t n = next++; n < order.size(); n = next++) measure(order[n]);
  };
  std::vector<std::future<void>> helpers;
  const auto extra = static_cast<std::size_t>(std::min<int>(threads, static_cast<int>(order.size()))) - 1;
  for (std::size_t t = 0; t < extra; ++t) helpers.push_back(std::async(std::launch::async, work));
  work();
  for (std::future<void>& h : helpers) h.get();
  return out;
}

}  // namespace fnet
