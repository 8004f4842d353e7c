// The standard column reduction of a Z/2 boundary matrix (Edelsbrunner-Letscher-Zomorodian),
// without clearing, compression or any other shortcut.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace fnet::reference {

// A column lists the row indices of its non-zero entries, ascending.
using Column = std::vector<std::size_t>;

// Reduces `boundary` (column j = boundary of simplex j, rows = earlier simplices) left to right:
// while column j's lowest entry is the lowest entry of an earlier column, add that column.
// Returns, for every column, the row of its lowest entry after reduction, or nullopt if it
// reduced to zero. Row i paired with column j means simplex i is born and j kills it.
std::vector<std::optional<std::size_t>> reduce_lowest_rows(std::vector<Column> boundary);

}  // namespace fnet::reference
