// The names a contract document lists, for tests that hold the code to its documents.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

namespace fnet::testing {

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every `name` in backticks in the part of `text` from `begin` (exclusive) to the first `end` after it.
inline std::set<std::string> backticked_between(const std::string& text, const std::string& begin,
                                                const std::string& end) {
  const std::size_t from = text.find(begin);
  if (from == std::string::npos) throw std::runtime_error("no '" + begin + "' in the document");
  const std::size_t to = text.find(end, from + begin.size());
  if (to == std::string::npos) throw std::runtime_error("no '" + end + "' after '" + begin + "'");
  std::set<std::string> names;
  for (std::size_t k = text.find('`', from + begin.size()); k < to; k = text.find('`', k + 1)) {
    const std::size_t close = text.find('`', k + 1);
    if (close == std::string::npos || close > to) break;
    names.insert(text.substr(k + 1, close - k - 1));
    k = close;
  }
  return names;
}

// The backticked names in the first column of the tables of the section headed `heading` (up to the
// next heading).
inline std::set<std::string> first_column_names(const std::string& text, const std::string& heading) {
  const std::size_t from = text.find("\n" + heading + "\n");
  if (from == std::string::npos) throw std::runtime_error("no heading '" + heading + "' in the document");
  const std::size_t to = std::min(text.find("\n#", from + 1), text.size());
  std::set<std::string> names;
  std::istringstream lines(text.substr(from, to - from));
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("|", 0) != 0) continue;
    const std::string cell = line.substr(1, line.find('|', 1) - 1);
    const std::set<std::string> in_cell = backticked_between("|" + cell + "|", "|", "|");
    names.insert(in_cell.begin(), in_cell.end());
  }
  return names;
}

}  // namespace fnet::testing
