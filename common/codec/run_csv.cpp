#include "common/codec/run_csv.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/codec/frame_csv.hpp"

namespace fnet {

std::vector<FrameHeader> read_csv_index(const std::filesystem::path& dir, const std::string& run_id) {
  const std::filesystem::path index = dir / "index.csv";
  std::ifstream in(index);
  if (!in) throw CsvError(index.string() + ": cannot open file");
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const auto split = [](const std::string& row) {
    std::vector<std::string> cells;
    std::string cell;
    for (std::stringstream s(row); std::getline(s, cell, ',');) cells.push_back(cell);
    return cells;
  };
  const std::vector<std::string> header = split(line);
  // The first of `names` the header has; a required column names the first of them when absent.
  const auto column = [&](std::initializer_list<const char*> names, bool required) -> int {
    for (const char* name : names)
      for (std::size_t k = 0; k < header.size(); ++k)
        if (header[k] == name) return static_cast<int>(k);
    if (required) throw CsvError(index.string() + ":1: header lacks column '" + *names.begin() + "'");
    return -1;
  };
  // fnet writes z; the LAMMPS reference data says Z.
  const int c_frame = column({"frame"}, true), c_step = column({"step"}, false), c_time = column({"time"}, false),
            c_rho = column({"rho"}, true), c_z = column({"z", "Z"}, true);
  std::vector<FrameHeader> out;
  std::size_t line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> cells = split(line);
    if (cells.size() != header.size())
      throw CsvError(index.string() + ":" + std::to_string(line_no) + ": expected " + std::to_string(header.size()) +
                     " fields");
    FrameHeader h;
    try {
      h.run_id = run_id;
      h.index = static_cast<std::uint32_t>(std::stoul(cells[c_frame]));
      // An experiment has no simulation step: its frames count in their place.
      h.step = c_step >= 0 ? std::stoull(cells[c_step]) : h.index;
      h.time = c_time >= 0 ? std::stod(cells[c_time]) : 0.0;
      h.rho = std::stod(cells[c_rho]);
      h.z = std::stod(cells[c_z]);
    } catch (const std::exception&) {
      throw CsvError(index.string() + ":" + std::to_string(line_no) + ": not a number in '" + line + "'");
    }
    out.push_back(std::move(h));
  }
  return out;
}

RunFrame read_csv_frame(const std::filesystem::path& dir, const FrameHeader& header) {
  char stem[32];
  std::snprintf(stem, sizeof stem, "frame_%04u", header.index);
  RunFrame f;
  f.header = header;
  f.frame = read_frame_csv(dir / (std::string(stem) + "_contacts.csv"), dir / (std::string(stem) + "_particles.csv"));
  f.frame.label = frame_label(header.run_id, header.index);
  return f;
}

std::vector<RunFrame> read_csv_run(const std::filesystem::path& dir, const std::string& run_id) {
  std::vector<RunFrame> out;
  for (const FrameHeader& header : read_csv_index(dir, run_id)) out.push_back(read_csv_frame(dir, header));
  return out;
}

}  // namespace fnet
