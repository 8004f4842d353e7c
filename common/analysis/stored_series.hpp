// The twelve distances fnet stores for every frame, in the one order every layer uses: the columns
// of a store's `distances` (its `series` attribute names them in this order, proto/store.md),
// StepDistances, the keys of the API's points, and the Python reader (which reads the attribute).
// Adding a stored metric is one entry in kMetrics (frame_analysis.hpp): the table follows.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "common/analysis/metric.hpp"
#include "common/topology/force_network.hpp"

namespace fnet {

struct StoredSeries {
  Metric metric = Metric::bottleneck;
  int dim = 0;
  ForceKind force = ForceKind::normal;
};

// Metric outermost, then the dimension, then the force.
inline constexpr std::array<StoredSeries, kMetrics.size() * 2 * kForces.size()> kStoredSeries = [] {
  std::array<StoredSeries, kMetrics.size() * 2 * kForces.size()> out{};
  std::size_t k = 0;
  for (const Metric metric : kMetrics)
    for (int dim = 0; dim < 2; ++dim)
      for (const ForceKind force : kForces) out[k++] = {metric, dim, force};
  return out;
}();

// The position of (metric, dim, force) in kStoredSeries.
constexpr std::size_t stored_series_index(Metric metric, int dim, ForceKind force) {
  for (std::size_t k = 0; k < kStoredSeries.size(); ++k)
    if (kStoredSeries[k].metric == metric && kStoredSeries[k].dim == dim && kStoredSeries[k].force == force) return k;
  return kStoredSeries.size();
}

// "wasserstein2/pd1/normal": how the API and the stores name a stored series.
std::string series_key(Metric metric, int dim, ForceKind force);
std::string series_key(const StoredSeries& s);
// The series a key names, if any.
std::optional<StoredSeries> parse_series_key(std::string_view key);

// The keys of kStoredSeries in order, comma-separated: the value of a store's `series` attribute.
std::string stored_series_layout();

}  // namespace fnet
