#include "common/codec/explain_json.hpp"

#include "common/codec/distance_json.hpp"

namespace fnet {

nlohmann::json to_json(const ExplainedSimplex& simplex) {
  nlohmann::json out{{"grains", simplex.grains}};
  if (!simplex.positions.empty()) {
    nlohmann::json positions = nlohmann::json::array();
    for (const auto& [x, y, z] : simplex.positions)
      positions.push_back(simplex.dimension == 3 ? nlohmann::json{x, y, z} : nlohmann::json{x, y});
    out["positions"] = std::move(positions);
  }
  return out;
}

nlohmann::json to_json(const ExplainedPoint& point) {
  return {{"birth", point.point.birth},
          {"death", point.point.death},
          {"birth_simplex", to_json(point.birth_simplex)},
          {"death_simplex", point.death_simplex ? to_json(*point.death_simplex) : nlohmann::json(nullptr)}};
}

nlohmann::json explain_terms_json(const std::vector<ExplainedTerm>& terms) {
  nlohmann::json out = nlohmann::json::array();
  const auto side = [](const std::optional<ExplainedPoint>& p) { return p ? to_json(*p) : nlohmann::json(nullptr); };
  for (const ExplainedTerm& t : terms)
    out.push_back({{"rank", t.rank}, {"cost", t.cost}, {"a", side(t.a)}, {"b", side(t.b)}});
  return out;
}

nlohmann::json explain_json(const Frame& a, const Frame& b, const ExplainRequest& request) {
  const Explanation e = explain(a, b, request);
  nlohmann::json out = to_json(e.distance);
  out["explain"] = explain_terms_json(e.terms);
  return out;
}

}  // namespace fnet
