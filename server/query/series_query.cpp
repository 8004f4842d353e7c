#include "server/query/series_query.hpp"

#include "server/query/query_errors.hpp"

namespace fnet::query {

SeriesAnswer series_query(const FrameLookup& frames, const SeriesRequest& r) {
  auto committed = frames.frames(r.run);
  if (!committed) throw UnknownRun(r.run);
  SeriesAnswer out{std::move(*committed), {}};
  out.values = series_values(out.frames, r.measure, r.range, with_diagrams(frames, r.run));
  return out;
}

}  // namespace fnet::query
