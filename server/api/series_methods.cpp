#include "server/api/series_methods.hpp"

#include <cmath>

#include "common/analysis/step_series.hpp"
#include "server/api/api_params.hpp"
#include "server/api/series_columns.hpp"

namespace fnet::server {
namespace {

using json = nlohmann::json;

// request -> query (series_values) -> codec (SeriesColumns).
json series_get(const Registry& registry, const json& params) {
  const SeriesMeasure measure = get_series_measure(params);
  const FrameRange range = get_frame_range(params);
  const std::string run = resolve_run(registry, params);
  const auto frames = registry.frames(run);
  if (!frames) unknown_run(run);
  const SeriesValues values = series_values(*frames, measure, range);

  json out = describe(measure.query);
  if (measure.denominator) out["ratio"] = measure.ratio;
  out["run"] = run;
  SeriesColumns columns;
  for (std::size_t k = 0; k < values.value.size(); ++k) {
    const std::optional<double>& v = values.value[k];
    const bool infinite = v && std::isinf(*v);
    columns.add(*(*frames)[values.first + k], v && std::isfinite(*v) ? json(*v) : json(nullptr), infinite);
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
