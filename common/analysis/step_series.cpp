#include "common/analysis/step_series.hpp"

#include <limits>

namespace fnet {

bool is_stored(const StepQuery& query) { return query.metric.stored && query.essential == EssentialConvention::floor; }

bool is_stored(const SeriesMeasure& measure) {
  return is_stored(measure.query) && (!measure.denominator || is_stored(*measure.denominator));
}

void append_step_values(std::span<const std::shared_ptr<const AnalyzedFrame>> frames, const StepQuery& query,
                        std::size_t from, std::vector<StepValue>& out, const WithDiagrams& whole) {
  const bool stored = is_stored(query);
  const auto read = [&](std::size_t k) { return whole ? whole(*frames[k]) : frames[k]; };
  std::shared_ptr<const AnalyzedFrame> before;  // frames[k - 1] with its diagrams, once read
  for (std::size_t k = from; k < frames.size(); ++k) {
    const AnalyzedFrame& f = *frames[k];
    StepValue step{f.header.index, f.header.rho, f.header.z, std::nullopt};
    std::shared_ptr<const AnalyzedFrame> now;
    if (f.previous && k > 0) {
      if (stored) {
        step.value = f.distances(*query.metric.stored, query.dim, query.force);
      } else {
        if (!before) before = read(k - 1);
        now = read(k);
        const DistanceResult r =
            choice_distance(diagram_of(before->diagrams, query.force, query.dim),
                            diagram_of(now->diagrams, query.force, query.dim), query.metric, query.essential);
        step.value = r.infinite ? std::numeric_limits<double>::infinity() : r.value;
      }
    }
    before = std::move(now);
    out.push_back(step);
  }
}

SeriesValues series_values(std::span<const std::shared_ptr<const AnalyzedFrame>> frames, const SeriesMeasure& measure,
                           const FrameRange& range, const WithDiagrams& whole) {
  SeriesValues out;
  std::size_t end = frames.size();
  while (out.first < end && range.from && frames[out.first]->header.index < *range.from) ++out.first;
  while (end > out.first && range.to && frames[end - 1]->header.index > *range.to) --end;
  std::vector<StepValue> top, bottom;
  append_step_values(frames.first(end), measure.query, out.first, top, whole);
  if (measure.denominator) append_step_values(frames.first(end), *measure.denominator, out.first, bottom, whole);
  for (std::size_t k = 0; k < top.size(); ++k) {
    if (!measure.denominator || !top[k].value)
      out.value.push_back(top[k].value);
    else
      out.value.push_back(*top[k].value / *bottom[k].value);
  }
  return out;
}

std::vector<CurveSample> curve_samples(std::span<const StepValue> steps, double shift, std::size_t run) {
  std::vector<CurveSample> out;
  out.reserve(steps.size());
  for (const StepValue& s : steps)
    if (s.value) out.push_back({s.rho - shift, s.z, *s.value, run});
  return out;
}

}  // namespace fnet
