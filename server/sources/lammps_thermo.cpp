#include "server/sources/lammps_thermo.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "server/sources/text_lines.hpp"

namespace fnet::sources {

namespace {

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

bool number(const std::string& word, double& value) {
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  return ec == std::errc() && end == word.data() + word.size();
}

}  // namespace

std::map<std::uint64_t, double> thermo_column(const std::filesystem::path& log, const std::string& column) {
  TextLines lines(log);
  std::map<std::uint64_t, double> out;
  std::string line;
  bool found = false;
  constexpr std::size_t none = static_cast<std::size_t>(-1);
  std::size_t at = none;  // the column's place in the current block; none outside a block
  std::size_t width = 0;
  while (lines.next(line)) {
    const std::vector<std::string> w = words(line);
    if (!w.empty() && w[0] == "Step") {
      at = none;
      for (std::size_t k = 0; k < w.size(); ++k)
        if (w[k] == column) at = k;
      width = w.size();
      found = found || at != none;
      continue;
    }
    if (line.rfind("Loop time of", 0) == 0 || line.rfind("WARNING", 0) == 0) {
      if (line.rfind("Loop", 0) == 0) at = none;
      continue;
    }
    if (at == none) continue;
    double step = 0, value = 0;
    // A step is LAMMPS's bigint, a whole number in [0, 2^63): any other is no step (and past 2^64
    // would not convert).
    if (w.size() != width || !number(w[0], step) || !number(w[at], value) || !(step >= 0 && step < 0x1p63) ||
        step != std::floor(step))
      throw std::runtime_error(log.string() + ":" + std::to_string(lines.number()) + ": a thermo row of " +
                               std::to_string(w.size()) + " values under " + std::to_string(width) +
                               " columns, or not numbers, or a step that is not a whole number below 2^63: \"" +
                               line.substr(0, 60) + "\"");
    out.emplace(static_cast<std::uint64_t>(step), value);
  }
  if (!found)
    throw std::runtime_error(log.string() + ": no thermo output names " + column + " (thermo_style custom step " +
                             column + ")");
  return out;
}

}  // namespace fnet::sources
