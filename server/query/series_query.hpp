// A run's distances between consecutive frames, or their ratio d_B / d_Wq, frame by frame
// (series.get).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/analysis/step_series.hpp"
#include "server/query/frame_lookup.hpp"

namespace fnet::query {

struct SeriesRequest {
  std::string run;
  SeriesMeasure measure;
  FrameRange range;
};

struct SeriesAnswer {
  std::vector<std::shared_ptr<const AnalyzedFrame>> frames;  // every committed frame of the run
  SeriesValues values;                                       // of the frames in the range
};

// UnknownRun when there is no such run.
SeriesAnswer series_query(const FrameLookup& frames, const SeriesRequest& request);

}  // namespace fnet::query
