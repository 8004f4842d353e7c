// blocks.get: where a run's force network changed between two frames, cell by cell over a k x k
// grid, k x k x k in a 3D run (common/analysis/blocks.hpp; proto/api.md).
#pragma once

#include <nlohmann/json.hpp>

#include "server/query/block_query.hpp"
#include "server/registry/run_registry.hpp"

namespace fnet::server {

// Every parameter is checked before the run is looked up; the networks are read back from the
// run's store, so this works on any stored frame, also after a restart.
nlohmann::json blocks_get(const Registry& registry, const nlohmann::json& params);

// The answer as proto/api.md writes it: a 3D grid's cells (and the largest) also carry their
// "layer", and their bounds z_lo, z_hi; a 2D one is written without them.
nlohmann::json blocks_json(const query::BlockRequest& request, const query::BlockAnswer& answer);

}  // namespace fnet::server
