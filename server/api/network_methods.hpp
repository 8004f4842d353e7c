// network.get: a committed frame's force network as its run's store keeps it — what the
// dashboard draws (proto/api.md).
#pragma once

#include <nlohmann/json.hpp>

#include "server/registry/run_registry.hpp"

namespace fnet::server {

// Every parameter is checked before the run is looked up; the network is read back from the run's
// store, so this works on any stored frame, also after a restart.
nlohmann::json network_get(const Registry& registry, const nlohmann::json& params);

}  // namespace fnet::server
