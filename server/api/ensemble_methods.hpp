// The methods of fnet-server that serve ensembles of realizations (proto/api.md): ensembles.list,
// ensemble.series, ensemble.subscribe, ensemble.unsubscribe.
#pragma once

#include <nlohmann/json.hpp>

#include "server/api/method.hpp"

namespace fnet::server {

// The four ensemble methods by name; their subscriptions end with their connection.
MethodTable ensemble_methods(ApiContext& context);

}  // namespace fnet::server
