// The methods of fnet-server that serve ensembles of realizations (proto/api.md): ensembles.list,
// ensemble.series, ensemble.subscribe, ensemble.unsubscribe; and series.get's `ratio`, a run's
// d_B / d_Wq frame by frame.
#pragma once

#include <nlohmann/json.hpp>

#include "server/api/api_methods.hpp"

namespace fnet::server {

// The four ensemble methods by name; their subscriptions end with their connection.
MethodTable ensemble_methods(ApiContext& context);

// series.get given `ratio`: the answer of series.get with value[k] = d_B / d_Wq of frame k.
nlohmann::json series_ratio_get(const Registry& registry, const nlohmann::json& params);

}  // namespace fnet::server
