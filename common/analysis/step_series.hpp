// A run's distances between consecutive committed frames, as series.get serves them and the
// ensemble curves bin them: the stored series where one answers the request (bottleneck, W1, W2
// under the floor convention), else computed from the two frames' diagrams.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/analysis/analyzed_frame.hpp"
#include "common/analysis/ensemble_curve.hpp"
#include "common/analysis/metric_vocabulary.hpp"

namespace fnet {

struct StepQuery {
  MetricChoice metric;
  int dim = 0;
  ForceKind force = ForceKind::normal;
  EssentialConvention essential = EssentialConvention::floor;
};

// What a series measures: one distance, or with `denominator` the ratio d_B / d_Wq frame by frame
// (query is then the bottleneck, its numerator).
struct SeriesMeasure {
  StepQuery query;
  std::optional<StepQuery> denominator;
  std::string ratio;  // "wasserstein1" | "wasserstein2" with a denominator, else empty
};

// Whether the values are read from the stored series (a metric of kStoredSeries under the floor
// convention) rather than computed from the frames' diagrams.
bool is_stored(const StepQuery& query);
bool is_stored(const SeriesMeasure& measure);

// Frame indices 'from'..'to', inclusive, each optional.
struct FrameRange {
  std::optional<std::uint32_t> from, to;
  bool contains(std::uint32_t index) const { return (!from || index >= *from) && (!to || index <= *to); }
};

// One committed frame; `value` (possibly +inf) is its distance from the frame committed before it,
// none for the first frame or one without a previous accepted frame.
struct StepValue {
  std::uint32_t index = 0;
  double rho = 0, z = 0;
  std::optional<double> value;
};

// A frame with its diagrams, given its row (a frame whose diagrams' points are not held, as
// fnet-server keeps them); empty: the frames given hold their diagrams.
using WithDiagrams = std::function<std::shared_ptr<const AnalyzedFrame>(const AnalyzedFrame& row)>;

// Frames in index order. Appends the values of frames[from...] to `out` (frames[from - 1] is
// their predecessor), so that a caller holding the values of a run's first frames computes only
// those committed since. A value computed from diagrams reads them through `whole`, two frames at
// a time.
void append_step_values(std::span<const std::shared_ptr<const AnalyzedFrame>> frames, const StepQuery& query,
                        std::size_t from, std::vector<StepValue>& out, const WithDiagrams& whole = {});

// The frames of `frames` (committed, in index order) that lie in `range`, and the value of each:
// none for a frame without a predecessor; a ratio 0/0 is NaN, x/0 and an infinite distance +inf.
// Computes only the frames in the range.
struct SeriesValues {
  std::size_t first = 0;  // frames[first + k] is the frame of value[k]
  std::vector<std::optional<double>> value;
};
SeriesValues series_values(std::span<const std::shared_ptr<const AnalyzedFrame>> frames, const SeriesMeasure& measure,
                           const FrameRange& range = {}, const WithDiagrams& whole = {});

// The samples a curve bins: each frame with a value, at rho - shift, as samples of realization `run`.
std::vector<CurveSample> curve_samples(std::span<const StepValue> steps, double shift = 0, std::size_t run = 0);

}  // namespace fnet
