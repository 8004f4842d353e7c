// fnet-analyze store: the analysis fnet-server does live, done offline into the same store file.
#include <iostream>
#include <map>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include "common/analysis/frame_analysis.hpp"
#include "common/store/analysis_store.hpp"
#include "server/analysis/commands.hpp"
#include "server/analysis/run_source.hpp"

namespace po = boost::program_options;

namespace fnet::analyze {

int store_command(const std::vector<std::string>& args) {
  po::options_description options(
      "usage: fnet-analyze store (--run-file F | --csv-dir DIR --run-id R) --data-dir D\n\n"
      "Analyzes every frame of a recorded run in index order (validation, diagrams of both force\n"
      "networks, the twelve distances to the previous accepted frame) and writes D/RUN.h5 in the\n"
      "schema fnet-server uses (proto/store.md), replacing any store of that run there.\n\n"
      "options");
  RunSource source;
  std::string data_dir;
  options.add_options()("help,h", "show this help");
  source.add_options(options);
  options.add_options()("data-dir", po::value(&data_dir)->required(), "directory of run stores");
  if (!parse_options(options, args)) return 0;
  auto [info, frames] = source.read();
  std::map<std::uint32_t, RunFrame*> ordered;  // first occurrence of each index wins, as live
  for (RunFrame& f : frames) ordered.try_emplace(f.header.index, &f);

  std::filesystem::create_directories(data_dir);
  const std::filesystem::path path = store_path(data_dir, info.run_id);
  std::filesystem::remove(path);
  StoreWriter store(path, info.run_id);
  store.write_info(info);
  std::optional<AnalyzedFrame> previous;
  std::size_t accepted = 0, rejected = 0;
  for (auto& [index, frame] : ordered) {
    try {
      validate(frame->frame);
    } catch (const FrameError& e) {
      store.append(RejectedFrame{index, e.what()});
      std::cerr << "fnet-analyze store: rejected " << e.what() << "\n";
      ++rejected;
      continue;
    }
    AnalyzedFrame current;
    current.header = frame->header;
    current.diagrams = analyze_frame(frame->frame);
    if (previous) {
      current.previous = previous->header.index;
      current.distances = step_distances(previous->diagrams, current.diagrams);
    }
    store.append(current);
    previous = std::move(current);
    ++accepted;
  }
  std::cout << nlohmann::json{{"run", info.run_id},
                              {"store", path.string()},
                              {"frames", accepted},
                              {"rejected", rejected}}
                   .dump()
            << "\n";
  return 0;
}

}  // namespace fnet::analyze
