// An explanation as a text table, the same in fnet-analyze explain and fnetctl explain: one row
// per term with its two points, the grains of the simplices that create and destroy them, and
// where the term sits in the packing.
#pragma once

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

namespace fnet {

// `answer`: a distance answer carrying "explain" (explain_json, or distance.get with explain: k).
// Where a term sits: "a (x, y)" for a point of the first frame matched to the diagonal, "b (x, y)"
// for one of the second, "a = b (x, y)" when both points' features are created at the same place,
// "a (x, y) b (x, y)" when they differ: the centre of the grains that create each feature, in d
// ("(x, y, z)" in a 3D frame); "-" without positions.
std::string explain_where(const nlohmann::json& term);

void write_explain_table(std::ostream& out, const nlohmann::json& answer, const std::string& metric_label);

}  // namespace fnet
