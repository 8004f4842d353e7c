// How fnetctl blocks prints blocks.get's answer: a table for the eye, or CSV with exact numbers,
// one row per cell. A 3D answer (dimension 3) adds each cell's layer, and z bounds to the CSV.
#pragma once

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

namespace fnet::client {

// "k x k", or "k x k x k" in 3D.
std::string grid_text(const nlohmann::json& answer);

void write_blocks_table(std::ostream& out, const nlohmann::json& answer);
void write_blocks_csv(std::ostream& out, const nlohmann::json& answer);

}  // namespace fnet::client
