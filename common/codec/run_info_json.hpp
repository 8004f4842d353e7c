// RunInfo as JSON: the form the API serves and the analysis store records.
#pragma once

#include <nlohmann/json.hpp>

#include "common/analysis/run_frame.hpp"

namespace fnet {

// {"run", "particles", "polydispersity", ..., "seed", "config": <config_json parsed, or the raw text>}
nlohmann::json to_json(const RunInfo& info);
// Inverse of to_json (also accepts the verbatim "config_json" text instead of "config"); throws
// nlohmann::json::exception on a missing or mistyped field.
RunInfo run_info_from_json(const nlohmann::json& value);

}  // namespace fnet
