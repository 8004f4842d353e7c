// The distance between two committed frames, of one run or of two, with on request the longest
// terms of the matching behind it (distance.get, fnet-analyze explain).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/analysis/explain.hpp"
#include "common/analysis/step_series.hpp"
#include "common/distance/distance_result.hpp"
#include "server/query/frame_lookup.hpp"

namespace fnet::query {

struct PairRequest {
  std::string run;
  std::uint32_t frame = 0;
  std::string other_run;
  std::uint32_t other_frame = 0;
  StepQuery measure;
  double delta = 0;                          // the accepted relative error (0: exact)
  std::optional<std::size_t> explain_terms;  // how many terms to explain (>= 1); none: no explanation
};

struct PairAnswer {
  DistanceResult distance;
  std::optional<std::vector<ExplainedTerm>> explained;  // present exactly when terms were asked for
  double seconds = 0;                                   // computing the distance and the terms
};

// The distance between the frames' diagrams; UnknownFrame (the first frame checked first) when a
// frame is not committed. The terms are computed from both frames' force networks (the diagrams
// do not hold the simplices that pair their points): NoNetwork when one cannot be had.
PairAnswer pair_query(const FrameLookup& frames, const PairRequest& request);

}  // namespace fnet::query
