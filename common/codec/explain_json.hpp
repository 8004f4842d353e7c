// JSON of an explanation, as `fnet-analyze explain` prints it and distance.get's `explain` carries:
//   [{"rank": 1, "cost": length, "a": point|null, "b": point|null}, ...]
//   point   = {"birth", "death" (-1: never dies), "birth_simplex": simplex, "death_simplex": simplex|null}
//   simplex = {"grains": [ids], "positions": [[x, y], ...]}  (positions absent without a particle table;
//             [x, y, z] each in a 3D frame)
// a or b null: that term's point is matched to the diagonal.
#pragma once

#include <nlohmann/json.hpp>

#include "common/analysis/explain.hpp"

namespace fnet {

nlohmann::json to_json(const ExplainedSimplex& simplex);
nlohmann::json to_json(const ExplainedPoint& point);
nlohmann::json explain_terms_json(const std::vector<ExplainedTerm>& terms);  // the `explain` array

// The one call a front end needs: explains two frames and returns the distance as to_json(
// DistanceResult) writes it, with "explain" added. Throws as explain() does.
nlohmann::json explain_json(const Frame& a, const Frame& b, const ExplainRequest& request);

}  // namespace fnet
