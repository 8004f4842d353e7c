// JSON codecs for diagrams: [[birth, death], ...] and the object fnet-analyze diagram prints.
#pragma once

#include <nlohmann/json.hpp>

#include "common/topology/diagram.hpp"
#include "common/topology/persistence.hpp"

namespace fnet {

nlohmann::json to_json(const Diagram& diagram);
nlohmann::json to_json(const FrameDiagrams& diagrams);  // {"pd0", "pd1", "vertices", "edges", "triangles"}

// Throws std::invalid_argument naming what is wrong (not an array of pairs, non-finite, birth < death).
Diagram diagram_from_json(const nlohmann::json& value);

}  // namespace fnet
