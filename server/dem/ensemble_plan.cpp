#include "server/dem/ensemble_plan.hpp"

#include <charconv>
#include <set>
#include <stdexcept>

namespace fnet::sim {
namespace {

std::uint64_t parse_seed(std::string_view text, std::string_view item) {
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size())
    throw std::invalid_argument("'" + std::string(item) + "' is not a seed or a range of seeds (N or N-M)");
  return v;
}

void replace_all(std::string& s, std::string_view what, const std::string& with) {
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + with.size()))
    s.replace(at, what.size(), with);
}

}  // namespace

std::vector<std::uint64_t> parse_seed_list(std::string_view spec) {
  if (spec.empty()) throw std::invalid_argument("empty: give seeds such as 1-20 or 1,3,5-7");
  std::vector<std::uint64_t> seeds;
  std::set<std::uint64_t> seen;
  const auto add = [&](std::uint64_t seed) {
    if (!seen.insert(seed).second) throw std::invalid_argument("seed " + std::to_string(seed) + " is listed twice");
    if (seeds.size() == kMaxSeeds) throw std::invalid_argument("more than " + std::to_string(kMaxSeeds) + " seeds");
    seeds.push_back(seed);
  };
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = spec.find(',', begin);
    const std::string_view item = spec.substr(begin, comma == std::string_view::npos ? spec.npos : comma - begin);
    if (item.empty()) throw std::invalid_argument("an empty item in '" + std::string(spec) + "'");
    const std::size_t dash = item.find('-');
    if (dash == std::string_view::npos) {
      add(parse_seed(item, item));
    } else {
      const std::uint64_t first = parse_seed(item.substr(0, dash), item);
      const std::uint64_t last = parse_seed(item.substr(dash + 1), item);
      if (last < first) throw std::invalid_argument("the range " + std::string(item) + " is reversed");
      if (last - first >= kMaxSeeds)
        throw std::invalid_argument("the range " + std::string(item) + " holds more than " + std::to_string(kMaxSeeds) +
                                    " seeds");
      for (std::uint64_t s = first;; ++s) {
        add(s);
        if (s == last) break;
      }
    }
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  return seeds;
}

std::string realization_run_id(const std::string& ensemble, std::uint64_t seed) {
  return ensemble + "-s" + std::to_string(seed);
}

bool names_each_realization(const std::string& path_template) {
  return path_template.find("{run}") != std::string::npos || path_template.find("{seed}") != std::string::npos;
}

std::string expand_path_template(const std::string& path_template, const std::string& run_id, std::uint64_t seed) {
  std::string path = path_template;
  replace_all(path, "{run}", run_id);
  replace_all(path, "{seed}", std::to_string(seed));
  return path;
}

}  // namespace fnet::sim
