// What an ensemble of realizations is made of before any of it runs: the seeds of --seeds and
// the per-realization paths its file flags name. Pure functions, so that a bad spec is refused
// before a single realization starts.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace fnet::sim {

inline constexpr std::size_t kMaxSeeds = 10000;

// "1-20", "1,3,5-7": comma-separated seeds and inclusive ranges, in the order given. Throws
// std::invalid_argument saying what is wrong (empty, an empty item, not a non-negative integer, a
// reversed range, a seed listed twice, more than kMaxSeeds).
std::vector<std::uint64_t> parse_seed_list(std::string_view spec);

// The run id of a realization: NAME-sSEED, as a single run with --ensemble NAME names itself.
std::string realization_run_id(const std::string& ensemble, std::uint64_t seed);

// A path flag of an ensemble must tell its realizations apart: it holds {run} (the run id) or
// {seed}, or every realization would write the same file.
bool names_each_realization(const std::string& path_template);
std::string expand_path_template(const std::string& path_template, const std::string& run_id, std::uint64_t seed);

}  // namespace fnet::sim
