// blocks.get: where a run's force network changed between two frames, cell by cell over a k x k
// grid (common/analysis/blocks.hpp; proto/api.md).
#pragma once

#include <nlohmann/json.hpp>

#include "server/registry/run_registry.hpp"

namespace fnet::server {

// Every parameter is checked before the run is looked up; the networks are read back from the
// run's store, so this works on any stored frame, also after a restart.
nlohmann::json blocks_get(const Registry& registry, const nlohmann::json& params);

}  // namespace fnet::server
