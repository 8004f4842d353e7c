#include "server/sources/lammps_dimension.hpp"

#include <sstream>
#include <stdexcept>
#include <vector>

#include "server/sources/text_lines.hpp"

namespace fnet::sources {

RunDimension dimension_flag(const std::string& text) {
  if (text != "2" && text != "3") throw std::invalid_argument("\"" + text + "\" is neither 2 nor 3");
  return {text == "3" ? 3 : 2, "--dimension"};
}

std::optional<RunDimension> logged_dimension(const std::filesystem::path& log) {
  TextLines lines(log);
  std::string line;
  while (lines.next(line)) {
    std::istringstream in(line.substr(0, line.find('#')));
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    if (words.size() == 2 && words[0] == "dimension" && (words[1] == "2" || words[1] == "3"))
      return RunDimension{words[1] == "3" ? 3 : 2, log.string() + ":" + std::to_string(lines.number())};
  }
  return std::nullopt;
}

RunDimension dimension_of_first_frame(const DumpSnapshot& atoms) {
  return {z_varies(atoms) ? 3 : 2, "the z of the first frame, " + atoms.where()};
}

}  // namespace fnet::sources
