#include "server/sources/run_source.hpp"

#include "common/codec/run_csv.hpp"
#include "common/run/run_names.hpp"
#include "common/store/analysis_store.hpp"
#include "common/store/run_file.hpp"
#include "server/sources/input_paths.hpp"

namespace fnet::sources {

namespace po = boost::program_options;

void RunSource::add_options(po::options_description& options) {
  options.add_options()("run-file", po::value(&run_file), "HDF5 run file written by fnet-simd --out")(
      "csv-dir", po::value(&csv_dir),
      "a run folder: index.csv (frame[,step][,time],rho,z; an experiment without steps may leave step "
      "out) + frame_NNNN_contacts.csv [+ frame_NNNN_particles.csv], as fnet-simd --export-csv writes it")(
      "run-id", po::value(&run_id), "run id (required with --csv-dir; overrides the run file's)")(
      "ensemble", po::value(&ensemble),
      "the ensemble of realizations the run belongs to (overrides the run file's; a CSV folder has none)");
}

std::pair<RunInfo, std::vector<RunFrame>> RunSource::read() const {
  if (run_file.empty() == csv_dir.empty()) throw po::error("give exactly one of --run-file and --csv-dir");
  if (!run_file.empty()) require_file("--run-file", run_file);
  if (!csv_dir.empty()) {
    require_directory("--csv-dir", csv_dir);
    if (run_id.empty()) throw po::error("--csv-dir needs --run-id");
  }
  if (!run_id.empty())
    if (const std::string problem = run_id_problem(run_id); !problem.empty()) throw po::error("--run-id: " + problem);
  if (!ensemble.empty())
    if (const std::string problem = name_problem(ensemble, "ensemble name"); !problem.empty())
      throw po::error("--ensemble: " + problem);
  RunInfo info;
  std::vector<RunFrame> frames;
  if (!run_file.empty()) {
    RunFileContents contents = read_run_file(run_file);
    info = std::move(contents.info);
    frames = std::move(contents.frames);
    if (!run_id.empty()) {  // relabel the file's run
      info.run_id = run_id;
      for (RunFrame& f : frames) {
        f.header.run_id = run_id;
        f.frame.label = frame_label(run_id, f.header.index);
      }
    }
  } else {
    frames = read_csv_run(csv_dir, run_id);  // labelled with run_id already
    info.run_id = run_id;
    info.frames = static_cast<std::uint32_t>(frames.size());
    info.config_json = "{}";
    if (!frames.empty()) info.particles = static_cast<std::uint32_t>(frames.front().frame.particle_count);
  }
  if (!ensemble.empty()) info.ensemble = ensemble;
  if (const std::string problem = run_id_problem(info.run_id); !problem.empty()) throw po::error(problem);
  return {std::move(info), std::move(frames)};
}

}  // namespace fnet::sources
