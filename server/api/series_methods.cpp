#include "server/api/series_methods.hpp"

#include <cmath>

#include "server/api/api_params.hpp"
#include "server/api/registry_frames.hpp"
#include "server/api/series_columns.hpp"
#include "server/api/served_query.hpp"
#include "server/query/series_query.hpp"

namespace fnet::server {
namespace {

using json = nlohmann::json;

// series.get: params -> SeriesRequest -> series_query -> SeriesColumns.
json series_get(const Registry& registry, const json& params) {
  query::SeriesRequest r;
  r.measure = get_series_measure(params);
  r.range = get_frame_range(params);
  r.run = resolve_run(registry, params);
  const query::SeriesAnswer a = served([&] { return query::series_query(RegistryFrames(registry), r); });

  json out = describe(r.measure.query);
  if (r.measure.denominator) out["ratio"] = r.measure.ratio;
  out["run"] = r.run;
  // The run's dimension, as its last committed frame has it: 3 makes rho a volume fraction.
  out["dimension"] = a.frames.empty() ? json(nullptr) : json(a.frames.back()->dimension);
  SeriesColumns columns;
  for (std::size_t k = 0; k < a.values.value.size(); ++k) {
    const std::optional<double>& v = a.values.value[k];
    const bool infinite = v && std::isinf(*v);
    columns.add(*a.frames[a.values.first + k], v && std::isfinite(*v) ? json(*v) : json(nullptr), infinite);
  }
  columns.put(out);
  return out;
}

}  // namespace

Method series_get_method(const Registry& registry) {
  return {{"metric", "q", "run", "dim", "force", "essential", "from", "to", "ratio"},
          [&registry](const json& params, const std::shared_ptr<rpc::Peer>&) -> Reply {
            // A stored series is read at once; one computed frame by frame from the diagrams is heavy.
            if (is_stored(get_series_measure(params))) return series_get(registry, params);
            return Deferred{[&registry, params] { return series_get(registry, params); }};
          }};
}

}  // namespace fnet::server
