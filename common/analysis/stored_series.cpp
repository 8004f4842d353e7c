#include "common/analysis/stored_series.hpp"

namespace fnet {

std::string series_key(Metric metric, int dim, ForceKind force) {
  return std::string(to_string(metric)) + "/pd" + std::to_string(dim) + "/" + std::string(to_string(force));
}

std::string series_key(const StoredSeries& s) { return series_key(s.metric, s.dim, s.force); }

std::optional<StoredSeries> parse_series_key(std::string_view key) {
  for (const StoredSeries& s : kStoredSeries)
    if (series_key(s) == key) return s;
  return std::nullopt;
}

std::string stored_series_layout() {
  std::string out;
  for (const StoredSeries& s : kStoredSeries) {
    if (!out.empty()) out += ',';
    out += series_key(s);
  }
  return out;
}

}  // namespace fnet
