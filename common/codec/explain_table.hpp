// An explanation as a text table, the same in fnet-analyze explain and fnetctl explain: one row
// per term with its two points, the grains of the simplices that create and destroy them, and
// where the term sits in the packing.
#pragma once

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

namespace fnet {

// `answer`: a distance answer carrying "explain" (explain_json, or distance.get with explain: k).
void write_explain_table(std::ostream& out, const nlohmann::json& answer, const std::string& metric_label);

}  // namespace fnet
