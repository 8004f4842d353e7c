// An ensemble's curve, or one run's: a distance (or the ratio d_B / d_Wq) between consecutive
// frames binned by rho or by rho - rho_J over the member runs (ensemble.series, ensemble.subscribe).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/analysis/ensemble_curve.hpp"
#include "common/analysis/step_series.hpp"
#include "server/query/frame_lookup.hpp"

namespace fnet::query {

enum class CurveAxis { rho, rho_minus_rho_j };

struct CurveRequest {
  std::string ensemble, run;  // exactly one is non-empty
  SeriesMeasure measure;      // the distance binned, or the ratio d_B / d_Wq
  RhoBinning binning;
  CurveAxis axis = CurveAxis::rho;
};

// The step values of each member run already computed, so that a subscription computes only the
// frames committed since its last update (they matter when a distance is not stored).
struct StepCache {
  std::map<std::string, std::vector<StepValue>> numerator, denominator;
};

struct Curve {
  std::vector<std::string> runs;  // the members binned, in name order
  // With CurveAxis::rho_minus_rho_j, the members left out: their frames give no rho_J.
  std::vector<std::string> runs_without_rho_j;
  std::vector<CurveBin> bins;
  // The members' frames left out, each with why: a header no curve can place (header_problem),
  // which a store written before headers were checked may hold.
  std::vector<std::string> left_out;
};

// Over the members as they are now (no members, no bins: an unknown run or ensemble is not an
// error here); reuses and extends `cache`.
Curve compute_curve(const FrameLookup& frames, const CurveRequest& request, StepCache& cache);

}  // namespace fnet::query
