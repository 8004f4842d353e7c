// fnetctl blocks: where a run's network changed between two frames, cell by cell (blocks.get).
#include <cstdio>
#include <iomanip>
#include <iostream>

#include "client/fnetctl/commands.hpp"
#include "client/fnetctl/csv_provenance.hpp"
#include "client/fnetctl/value_text.hpp"
#include "client/rpc/rpc_client.hpp"
#include "common/analysis/blocks.hpp"

namespace po = boost::program_options;

namespace fnet::client {
namespace {

void print_csv(const json& r) {
  std::cout << "row,col,x_lo,x_hi,y_lo,y_hi,other_x_lo,other_x_hi,other_y_lo,other_y_hi,contacts,other_contacts,"
               "points,other_points,value\n";
  for (const json& c : r["cells"]) {
    std::cout << c["row"].get<int>() << "," << c["col"].get<int>();
    for (const json& bounds : c["bounds"])
      for (const json& v : bounds) std::cout << "," << exact_number(v.get<double>());
    std::cout << "," << c["contacts"][0].get<std::size_t>() << "," << c["contacts"][1].get<std::size_t>() << ","
              << c["points"][0].get<std::size_t>() << "," << c["points"][1].get<std::size_t>() << ","
              << distance_cell(c["value"], c["infinite"].get<bool>(), CellStyle::csv) << "\n";
  }
}

void print_table(const json& r) {
  std::cout << "run " << r["run"].get<std::string>() << ", frames " << r["frame"] << " and " << r["other_frame"] << ", "
            << r["k"] << " x " << r["k"] << " blocks, " << r["metric"].get<std::string>()
            << (r.contains("q") && r["metric"] == "wasserstein" ? " q=" + exact_number(r["q"].get<double>()) : "")
            << ", PD" << r["dim"].get<int>() << ", " << r["force"].get<std::string>()
            << " forces, essential=" << r["essential"].get<std::string>()
            << "; row 0 = lowest y, col 0 = lowest x; * the largest\n"
            << std::setw(4) << "row" << std::setw(5) << "col" << std::setw(18) << "contacts" << std::setw(16)
            << "points" << std::setw(16) << "value"
            << "\n";
  const json& largest = r["largest"];
  for (const json& c : r["cells"]) {
    const std::string contacts = std::to_string(c["contacts"][0].get<std::size_t>()) + " / " +
                                 std::to_string(c["contacts"][1].get<std::size_t>());
    const std::string points =
        std::to_string(c["points"][0].get<std::size_t>()) + " / " + std::to_string(c["points"][1].get<std::size_t>());
    const bool is_largest = c["row"] == largest["row"] && c["col"] == largest["col"];
    std::cout << std::setw(4) << c["row"].get<int>() << std::setw(5) << c["col"].get<int>() << std::setw(18) << contacts
              << std::setw(16) << points << std::setw(16)
              << distance_cell(c["value"], c["infinite"].get<bool>(), CellStyle::table) << (is_largest ? " *" : "")
              << "\n";
  }
}

}  // namespace

int blocks_command(const Endpoint& at, const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl blocks --frame A --other-frame B --metric M [options]\n\n"
      "Cuts both frames' force networks into a k x k grid over each frame's domain (the bounding box\n"
      "of its grains) and prints the distance between the diagrams of each cell (blocks.get; a\n"
      "contact belongs to the cell holding its contact point).\n\noptions");
  SeriesOptions c;
  c.add(o, true);
  std::string format = "table";
  long long frame = 0, other = 0, k = 2;
  o.add_options()("frame", po::value(&frame)->required(), "first frame")(
      "other-frame", po::value(&other)->required(), "second frame")("k", po::value(&k)->default_value(2),
                                                                    "blocks per side: 1 to 16")(
      "format", po::value(&format)->default_value("table"),
      "table, csv (one row per cell, exact numbers) or json (the API's answer)");
  po::variables_map vm;
  if (!parse_command(o, args, &vm)) return kOk;
  format_option(format, {"table", "csv", "json"});
  if (k < kMinBlocks || k > kMaxBlocks)
    throw po::error("--k must be an integer from " + std::to_string(kMinBlocks) + " to " + std::to_string(kMaxBlocks) +
                    ", got " + std::to_string(k));
  json p = c.checked(vm);
  p["frame"] = frame_option("--frame", frame);
  p["other_frame"] = frame_option("--other-frame", other);
  p["k"] = k;
  RpcClient rpc(at.host, at.port, std::chrono::seconds(30), at.token);
  const json r = rpc.call("blocks.get", p);
  if (format == "json")
    std::cout << r.dump() << "\n";
  else if (format == "csv") {
    std::cout << csv_provenance_line(rpc,
                                     "run " + r["run"].get<std::string>() + " frames " + r["frame"].dump() + " and " +
                                         r["other_frame"].dump() + ", " + r["k"].dump() + " x " + r["k"].dump() +
                                         " blocks (each normalized by its own mean force), " +
                                         r["metric"].get<std::string>() + " PD" + r["dim"].dump() + ", " +
                                         r["force"].get<std::string>() + " forces",
                                     r["essential"].get<std::string>())
              << "\n";
    print_csv(r);
  } else
    print_table(r);
  return kOk;
}

}  // namespace fnet::client
