#include "server/fnet-simd/simd_options.hpp"

#include <iostream>

#include "common/build_info/build_info.hpp"
#include "common/codec/command_line.hpp"
#include "common/run/run_names.hpp"

namespace fnet::sim {
namespace {

namespace po = boost::program_options;

constexpr const char* kUsage =
    "usage: fnet-simd [options]\n"
    "\n"
    "Runs the compression of Kramár et al. (2014): 2D polydisperse frictional disks in a box of rough\n"
    "walls (sized so that the grains fill --rho-initial of it), relaxed from a square lattice with\n"
    "random velocities until the grains are at rest (velocities damped during the relaxation only),\n"
    "then compressed by walls moving inward at v_c until rho = rho_final, with frames at fixed time\n"
    "intervals over the compression.\n"
    "Units: lengths in d_ave, masses in the mean grain mass, speeds in d_ave/tau_c, times in tau_c\n"
    "(k_n in m g/d_ave as in the paper). Parameters: defaults, then --config, then flags.\n"
    "\n"
    "Output: --export-csv DIR writes DIR/index.csv (frame,step,time,rho,z) and per frame\n"
    "DIR/frame_NNNN_particles.csv (id,x,y,r), DIR/frame_NNNN_contacts.csv (i,j,fn,ft; the input of\n"
    "'fnet-analyze diagram') and DIR/frame_NNNN_wall_contacts.csv (grain,wall,side,fn,ft), and\n"
    "DIR/provenance.json (fnet's version and commit, the date, the run's parameters and seed).\n"
    "Frames are published on Cyclone DDS (topics fnet_RunInfo, fnet_ForceFrame; reliable, keep-all,\n"
    "transient-local) on --domain (default 0; fnet-server must use the same) unless --no-dds;\n"
    "--out FILE also writes them to an HDF5 run file. With DDS as the only output, a run whose frames\n"
    "no subscriber matched exits 3 (the frames are lost), naming the domain. A run that a fnet-server\n"
    "reading it cannot store (its store fault: a full disk, no file descriptor left) exits 4, naming\n"
    "the run, the server and the reason.\n"
    "\n"
    "Checkpoints: with --checkpoint FILE (default DIR/checkpoint.fnetsim with --export-csv) the state\n"
    "is saved after every frame, every --checkpoint-interval seconds and on SIGINT/SIGTERM;\n"
    "--resume continues from it and produces frames bitwise identical to an uninterrupted run.\n"
    "\n"
    "Ensembles: --ensemble NAME --seeds 1-20 --jobs 2 runs one realization per seed (run ids NAME-sSEED),\n"
    "at most --jobs at a time, each a child fnet-simd doing a single run as above with the other flags.\n"
    "Each realization needs files of its own: --out, --export-csv, --checkpoint and --write-lammps-data\n"
    "must hold {run} (the run id) or {seed}, e.g. --out runs/{run}.h5. Its checkpoint is the one named,\n"
    "else checkpoint.fnetsim in its CSV folder, else {run}.fnetsim; its stderr goes to the checkpoint's\n"
    "name with .log. Progress is one line per realization and change (started, frame K/N, finished,\n"
    "stopped, failed with its exit code). SIGINT/SIGTERM stops every running realization at its\n"
    "checkpoint (exit 130); the same command again resumes those and skips the ones whose checkpoint\n"
    "holds the last frame. Exit 1 when any realization failed (named), 2 for a bad command line.\n"
    "Threads: each realization takes --threads (default 1), so --jobs x --threads in all.\n"
    "\n"
    "options";

}  // namespace

std::optional<SimdOptions> parse_simd_options(int argc, char** argv) {
  const Params defaults;
  po::options_description options(kUsage);
  SimdOptions o;
  auto& [params, config, export_dir, checkpoint_path, run_id, ensemble, lammps_data, out_file, checkpoint_interval,
         linger, ack_timeout, domain, threads, events_fd, flags, given, vm] = o;
  options.add_options()("help,h", "show this help")("version", "print the version and commit, then exit")(
      "config", po::value(&config), "JSON object of parameters (keys: the names in --show-params)");
  // The physics flags come from the parameter table; their values are parsed by it (a count
  // given as "-5" is an error there, not a wrapped-around integer).
  for (const ParamField& f : param_fields()) {
    flags.push_back(flag_name(f).substr(2));
    options.add_options()(flags.back().c_str(), po::value<std::string>(),
                          (std::string(f.help) + " (default " + format_value(defaults, f) + ")").c_str());
  }
  options.add_options()("threads", po::value(&threads)->default_value(1),
                        "threads for the time steps (forces and the Gear step); the results are the same bits for any "
                        "count")("run-id", po::value(&run_id),
                                 "run identifier carried by every frame, [A-Za-z0-9._-]{1,64} (default "
                                 "<ensemble>-s<S> with --ensemble, else fnet-simd-seed<S>)")(
      "ensemble", po::value(&ensemble),
      "the ensemble of realizations (one setting, several seeds) this run belongs to, announced with it; "
      "[A-Za-z0-9._-]{1,64}")("export-csv", po::value(&export_dir), "write frames as CSV files into this directory")(
      "out", po::value(&out_file),
      "write the run (parameters and every frame) to this HDF5 file, readable while it is written (proto/run_file.md)")(
      "no-dds", "do not publish frames over DDS")("domain", po::value(&domain)->default_value(0),
                                                  "DDS domain id (configure Cyclone DDS with CYCLONEDDS_URI)")(
      "ack-timeout", po::value(&ack_timeout)->default_value(60),
      "seconds to wait at the end until every subscriber acknowledged every frame")(
      "linger", po::value(&linger)->default_value(0),
      "seconds to keep serving late subscribers from the durability history after the last frame")(
      "checkpoint", po::value(&checkpoint_path), "checkpoint file")(
      "checkpoint-interval", po::value(&checkpoint_interval)->default_value(60), "seconds between checkpoints")(
      "resume", "continue the run saved in the checkpoint file (its parameters are used)")(
      "write-lammps-data", po::value(&lammps_data), "write the initial state as a LAMMPS data file, then run")(
      "show-params", "print the parameters and derived constants as JSON and exit")("quiet,q",
                                                                                    "no progress reports on stderr")(
      "seeds", po::value<std::string>(),
      "run an ensemble (needs --ensemble): one realization per seed, a list of seeds and ranges such as 1-20 or "
      "1,3,5-7")("jobs", po::value<unsigned>()->default_value(1), "with --seeds: realizations run at once");
  // Set by the ensemble that started this run: "frame K" is written there after each frame.
  po::options_description hidden;
  hidden.add_options()("events-fd", po::value(&events_fd));
  po::options_description all;
  all.add(options).add(hidden);
  const po::parsed_options parsed = po::parse_command_line(argc, argv, all);
  refuse_stray_arguments(parsed);
  given = parsed.options;
  po::store(parsed, vm);
  if (vm.count("help")) {
    std::cout << options << "\n";
    return std::nullopt;
  }
  if (vm.count("version")) {
    std::cout << fnet::version_line("fnet-simd") << "\n";
    return std::nullopt;
  }
  po::notify(vm);

  Params& p = params;
  p = defaults;
  if (!config.empty()) apply_config_file(p, config);
  for (const ParamField& f : param_fields()) {
    const std::string flag = flag_name(f).substr(2);
    if (vm.count(flag)) set_from_text(p, f, vm[flag].as<std::string>());
  }
  validate(p);
  if (vm.count("run-id")) {
    if (const std::string problem = fnet::run_id_problem(run_id); !problem.empty())
      throw po::error("--run-id: " + problem);
  }
  if (vm.count("ensemble")) {
    if (const std::string problem = fnet::name_problem(ensemble, "ensemble name"); !problem.empty())
      throw po::error("--ensemble: " + problem);
  }
  if (threads < 1 || threads > 256) throw po::error("--threads must be between 1 and 256");
  return o;
}

}  // namespace fnet::sim
