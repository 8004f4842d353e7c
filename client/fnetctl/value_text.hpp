// How fnetctl writes numbers. CSV and JSON carry the exact double (a spreadsheet or a script must
// read back what the server computed); tables round for the eye. An infinite distance is `inf`,
// never confused with the missing value of a frame that has no previous frame.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace fnet::client {

// The shortest text that reads back to the same bits (std::to_chars); "inf" / "-inf" / "nan".
std::string exact_number(double value);

// `significant` digits, for tables.
std::string rounded_number(double value, int significant);

enum class CellStyle { table, csv };

// A distance as a table or CSV cell: the number (rounded to 8 digits in tables, exact in CSV),
// "inf" when `infinite`, and "-" (table) or "" (CSV) for null: the frame has no previous frame.
std::string distance_cell(const nlohmann::json& value, bool infinite, CellStyle style);

}  // namespace fnet::client
