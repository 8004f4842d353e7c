// RunInfo as JSON: the form the API serves and the analysis store records.
#pragma once

#include <nlohmann/json.hpp>

#include "common/codec/bounded_json.hpp"
#include "common/run/run_frame.hpp"

namespace fnet {

// An announcement as JSON (the analysis store's 16 KiB rows), and the config_json it carries, are
// read within these limits: a config nests a few levels.
inline constexpr JsonLimits kAnnouncementJsonLimits{16384, 32};

// How a field holding JSON text (config_json) is written: `parsed` under its key ("config": the
// parameters as a JSON value, or the raw text as a string if it does not parse within
// kAnnouncementJsonLimits), as the API serves
// it; `verbatim` under its member name ("config_json": the text itself), as the analysis store
// records it, so that it reads back unchanged.
enum class JsonText { parsed, verbatim };

// {"run", "particles", "polydispersity", ..., "seed", "config"}: one key per field of
// for_each_run_info_field.
nlohmann::json to_json(const RunInfo& info, JsonText text = JsonText::parsed);
// Inverse of to_json in either form; throws nlohmann::json::exception on a missing or mistyped field.
RunInfo run_info_from_json(const nlohmann::json& value);

}  // namespace fnet
