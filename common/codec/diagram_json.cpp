#include "common/codec/diagram_json.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace fnet {

nlohmann::json to_json(const Diagram& diagram) {
  nlohmann::json out = nlohmann::json::array();
  for (const PersistencePoint& p : diagram) out.push_back({p.birth, p.death});
  return out;
}

nlohmann::json to_json(const FrameDiagrams& d) {
  return {{diagram_key(0), to_json(d.pd0)},
          {diagram_key(1), to_json(d.pd1)},
          {"vertices", d.vertices},
          {"edges", d.edges},
          {"triangles", d.triangles}};
}

Diagram diagram_from_json(const nlohmann::json& value) {
  if (!value.is_array()) throw std::invalid_argument("a diagram must be an array of [birth, death] pairs");
  Diagram out;
  out.reserve(value.size());
  for (std::size_t k = 0; k < value.size(); ++k) {
    const auto& p = value[k];
    const std::string where = "point " + std::to_string(k);
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      throw std::invalid_argument(where + ": expected [birth, death], got " + p.dump());
    const double birth = p[0].get<double>(), death = p[1].get<double>();
    if (!std::isfinite(birth) || !std::isfinite(death)) throw std::invalid_argument(where + ": non-finite value");
    if (death != kNeverDies && birth < death)
      throw std::invalid_argument(where + ": birth " + p[0].dump() + " < death " + p[1].dump() +
                                  " (superlevel diagrams have birth >= death)");
    out.push_back({birth, death});
  }
  return out;
}

std::string diagram_key(int dim) { return "pd" + std::to_string(dim); }

Diagram document_diagram(const nlohmann::json& document, int dim) {
  const std::string key = diagram_key(dim);
  if (!document.is_object() || !document.contains(key))
    throw std::invalid_argument("no \"" + key +
                                "\" diagram (expected a diagram document {\"pd0\": [...], \"pd1\": [...]})");
  try {
    return diagram_from_json(document[key]);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(key + ": " + e.what());
  }
}

}  // namespace fnet
