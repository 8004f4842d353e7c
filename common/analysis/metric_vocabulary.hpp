// The words users type for what fnet measures, one vocabulary for fnet-server, fnet-analyze and
// fnetctl: metric names (with the exponent q), force networks, diagram dimensions, and the key
// "metric/pdD/force" under which a stored series is named.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "common/analysis/frame_analysis.hpp"

namespace fnet {

inline constexpr std::array<std::string_view, 4> kMetricNames{"bottleneck", "wasserstein1", "wasserstein2",
                                                              "wasserstein"};

// A metric as requested: the name typed, its exponent, and which of the three series fnet stores
// per frame answers it (none for a Wasserstein exponent other than 1 and 2).
struct MetricChoice {
  std::string name;              // one of kMetricNames
  std::optional<double> q;       // the Wasserstein exponent; none for the bottleneck (q = infinity)
  std::optional<Metric> stored;  // the stored series equal to this metric, if any

  bool is_bottleneck() const { return !q.has_value(); }
  // The value the maths computes with.
  DistanceMetric distance() const;
  // "bottleneck", "wasserstein1", "wasserstein2", or "wasserstein q=3.5".
  std::string label() const;
};

// Checks the pair as users give it: bottleneck takes no q; wasserstein1 and wasserstein2 accept
// only their own q; wasserstein needs a finite q >= 1. Throws std::invalid_argument with a
// message naming the offending word or value.
MetricChoice parse_metric(std::string_view name, std::optional<double> q = std::nullopt);

// Force networks are named by parse_force_kind / to_string(ForceKind) (common/topology).
// 0 | 1; throws std::invalid_argument naming the value otherwise.
int check_dim(long long dim);

// The diagram a request means when it names none: PD1, the loops, as proto/api.md documents it for
// every front end (the API, fnetctl, fnet-analyze; the Python package states the same value).
inline constexpr int kDefaultDim = 1;

// series_key names a stored series (stored_series.hpp).

// The distance a choice names, computed exactly (delta 0) or to relative error delta.
DistanceResult choice_distance(const Diagram& a, const Diagram& b, const MetricChoice& metric,
                               EssentialConvention essential = EssentialConvention::floor, double delta = 0);

}  // namespace fnet
