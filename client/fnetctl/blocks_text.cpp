#include "client/fnetctl/blocks_text.hpp"

#include <iomanip>

#include "client/fnetctl/value_text.hpp"

namespace fnet::client {
namespace {

// A 3D answer's cells carry a layer and z bounds (proto/api.md).
bool three_d(const nlohmann::json& r) { return r.value("dimension", 2) == 3; }

}  // namespace

std::string grid_text(const nlohmann::json& r) {
  const std::string k = r["k"].dump();
  return three_d(r) ? k + " x " + k + " x " + k : k + " x " + k;
}

void write_blocks_csv(std::ostream& out, const nlohmann::json& r) {
  if (three_d(r))
    out << "layer,row,col,x_lo,x_hi,y_lo,y_hi,z_lo,z_hi,other_x_lo,other_x_hi,other_y_lo,other_y_hi,other_z_lo,"
           "other_z_hi,contacts,other_contacts,points,other_points,value\n";
  else
    out << "row,col,x_lo,x_hi,y_lo,y_hi,other_x_lo,other_x_hi,other_y_lo,other_y_hi,contacts,other_contacts,"
           "points,other_points,value\n";
  for (const nlohmann::json& c : r["cells"]) {
    if (three_d(r)) out << c["layer"].get<int>() << ",";
    out << c["row"].get<int>() << "," << c["col"].get<int>();
    for (const nlohmann::json& bounds : c["bounds"])
      for (const nlohmann::json& v : bounds) out << "," << exact_number(v.get<double>());
    out << "," << c["contacts"][0].get<std::size_t>() << "," << c["contacts"][1].get<std::size_t>() << ","
        << c["points"][0].get<std::size_t>() << "," << c["points"][1].get<std::size_t>() << ","
        << distance_cell(c["value"], c["infinite"].get<bool>(), CellStyle::csv) << "\n";
  }
}

void write_blocks_table(std::ostream& out, const nlohmann::json& r) {
  const bool layers = three_d(r);
  out << "run " << r["run"].get<std::string>() << ", frames " << r["frame"] << " and " << r["other_frame"] << ", "
      << grid_text(r) << " blocks, " << r["metric"].get<std::string>()
      << (r.contains("q") && r["metric"] == "wasserstein" ? " q=" + exact_number(r["q"].get<double>()) : "") << ", PD"
      << r["dim"].get<int>() << ", " << r["force"].get<std::string>()
      << " forces, essential=" << r["essential"].get<std::string>() << (layers ? "; layer 0 = lowest z" : "")
      << "; row 0 = lowest y, col 0 = lowest x; * the largest\n";
  if (layers) out << std::setw(6) << "layer";
  out << std::setw(4) << "row" << std::setw(5) << "col" << std::setw(18) << "contacts" << std::setw(16) << "points"
      << std::setw(16) << "value"
      << "\n";
  const nlohmann::json& largest = r["largest"];
  for (const nlohmann::json& c : r["cells"]) {
    const std::string contacts = std::to_string(c["contacts"][0].get<std::size_t>()) + " / " +
                                 std::to_string(c["contacts"][1].get<std::size_t>());
    const std::string points =
        std::to_string(c["points"][0].get<std::size_t>()) + " / " + std::to_string(c["points"][1].get<std::size_t>());
    const bool is_largest =
        c["row"] == largest["row"] && c["col"] == largest["col"] && (!layers || c["layer"] == largest["layer"]);
    if (layers) out << std::setw(6) << c["layer"].get<int>();
    out << std::setw(4) << c["row"].get<int>() << std::setw(5) << c["col"].get<int>() << std::setw(18) << contacts
        << std::setw(16) << points << std::setw(16)
        << distance_cell(c["value"], c["infinite"].get<bool>(), CellStyle::table) << (is_largest ? " *" : "") << "\n";
  }
}

}  // namespace fnet::client
