// fnet-analyze store: the analysis fnet-server does live, done offline into the same store file.
#include <iostream>
#include <variant>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include "common/analysis/run_pipeline.hpp"
#include "common/store/analysis_store.hpp"
#include "server/fnet-analyze/commands.hpp"
#include "server/sources/run_source.hpp"
#include "server/sources/source_kinds.hpp"

namespace po = boost::program_options;

namespace fnet::analyze {

int store_command(const std::vector<std::string>& args) {
  const std::vector<sources::SourceKind> kinds = sources::run_kinds();
  po::options_description options(
      "usage: fnet-analyze store " + sources::run_usage(kinds) +
      " [--ensemble E] --data-dir D\n\n"
      "Analyzes every frame of a recorded run in index order (validation, diagrams of both force\n"
      "networks, the twelve distances to the previous accepted frame) and writes D/RUN.h5 in the\n"
      "schema fnet-server uses (proto/store.md), replacing any store of that run there.\n\n"
      "options");
  std::string data_dir;
  options.add_options()("help,h", "show this help");
  sources::add_run_options(kinds, options);
  options.add_options()("data-dir", po::value(&data_dir)->required(), "directory of run stores");
  const auto vm = parse_options(options, args);
  if (!vm) return 0;
  const std::unique_ptr<sources::FrameSource> source = sources::open_run(kinds, *vm);
  const RunInfo& info = source->announcement();
  // Every frame is read before the store is touched: input that cannot be read leaves any store
  // of the run as it was.
  std::vector<RunFrame> frames;
  while (std::optional<RunFrame> frame = source->next()) frames.push_back(std::move(*frame));
  std::filesystem::create_directories(data_dir);
  const std::filesystem::path path = store_path(data_dir, info.run_id);
  std::filesystem::remove(path);
  StoreWriter store(path, info.run_id);
  store.write_info(info);
  // The server's pipeline, fed the input's frames as if they had all arrived at once: a repeated
  // index counts once (its first occurrence), and a missing one is skipped when the run ends.
  RunPipeline pipeline;
  const auto write = [&](std::vector<Settlement> settled) {
    for (const Settlement& s : settled) {
      if (const auto* accepted = std::get_if<std::shared_ptr<const AnalyzedFrame>>(&s)) {
        store.append(**accepted);
      } else if (const auto* rejected = std::get_if<RejectedFrame>(&s)) {
        store.append(*rejected);
        std::cerr << "fnet-analyze store: rejected " << rejected->reason << "\n";
      } else if (const auto* skipped = std::get_if<SkippedFrames>(&s)) {
        std::cerr << "fnet-analyze store: run " << info.run_id << " has no frames " << skipped->first << ".."
                  << skipped->last << "\n";
      }
    }
  };
  const auto now = PipelineClock::now();
  for (RunFrame& frame : frames) write(pipeline.push(std::move(frame), now));
  write(pipeline.finish());
  const std::size_t accepted = pipeline.counts().accepted, rejected = pipeline.counts().rejected;
  std::cout << nlohmann::json{{"run", info.run_id},
                              {"store", path.string()},
                              {"frames", accepted},
                              {"rejected", rejected}}
                   .dump()
            << "\n";
  return 0;
}

}  // namespace fnet::analyze
