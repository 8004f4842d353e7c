// fnetctl blocks: where a run's network changed between two frames, cell by cell (blocks.get).
#include <iostream>

#include "client/fnetctl/blocks_text.hpp"
#include "client/fnetctl/commands.hpp"
#include "client/fnetctl/csv_provenance.hpp"
#include "client/rpc/rpc_client.hpp"
#include "common/analysis/blocks.hpp"

namespace po = boost::program_options;

namespace fnet::client {

int blocks_command(const Endpoint& at, const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl blocks --frame A --other-frame B --metric M [options]\n\n"
      "Cuts both frames' force networks into a k x k grid over each frame's domain (the bounding box\n"
      "of its grains; k x k x k in a 3D run, each cell with its layer) and prints the distance between\n"
      "the diagrams of each cell (blocks.get; a contact belongs to the cell holding its contact point).\n\noptions");
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
  RpcClient rpc(at.host, at.port, std::chrono::seconds(30), at.token, at.tls);
  const json r = rpc.call("blocks.get", p);
  if (format == "json")
    std::cout << r.dump() << "\n";
  else if (format == "csv") {
    std::cout << csv_provenance_line(rpc,
                                     "run " + r["run"].get<std::string>() + " frames " + r["frame"].dump() + " and " +
                                         r["other_frame"].dump() + ", " + grid_text(r) +
                                         " blocks (each normalized by its own mean force), " +
                                         r["metric"].get<std::string>() + " PD" + r["dim"].dump() + ", " +
                                         r["force"].get<std::string>() + " forces",
                                     r["essential"].get<std::string>())
              << "\n";
    write_blocks_csv(std::cout, r);
  } else
    write_blocks_table(std::cout, r);
  return kOk;
}

}  // namespace fnet::client
