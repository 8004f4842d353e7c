// "Did you mean": the known names closest to a mistyped one, for the errors that name an unknown
// run or ensemble.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace fnet::server {

// Levenshtein distance (insertions, deletions, substitutions of bytes).
std::size_t edit_distance(const std::string& a, const std::string& b);

// Up to `most` of `names` close to `wanted`, closest first (ties by name): those within an edit
// distance of max(2, |wanted| / 3), and those that contain `wanted` or that it contains.
std::vector<std::string> close_names(const std::vector<std::string>& names, const std::string& wanted,
                                     std::size_t most = 5);

}  // namespace fnet::server
