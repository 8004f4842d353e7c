// JSON for distance results: {"value", "lower", "upper", "exact"}; an infinite distance is
// {"value": null, "lower": null, "upper": null, "exact": true, "infinite": true, "reason": "..."}.
#pragma once

#include <nlohmann/json.hpp>

#include "common/distance/distance_result.hpp"

namespace fnet {

nlohmann::json to_json(const DistanceResult& result);

}  // namespace fnet
